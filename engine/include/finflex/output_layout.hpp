// Where and how a batch's outputs are written: one descriptor per attribute (the
// model: OpenSubdiv's buffer descriptors, ozz-animation's spans with byte strides), so
// the kernels write straight into a renderer's own vertex buffers, in its layout and
// precision.
//
// An attribute (positions, normals, tangents, previous-frame positions) of instance i
// and vertex v (a slot, or the mesh's own vertex index with VertexOrder::kMesh) lives
// at, in bytes from its buffer's start:
//
//   packed: offset + i * instance_stride + v * vertex_stride, the element's components
//           one after the other (format_bytes(format) bytes in all);
//   planes: offset + i * instance_stride + (c * plane_stride + v) * component_bytes
//           for component c (x, y, z): structure-of-arrays, plane_stride elements a
//           plane (FinFlex's default, finflex/batch.hpp: what keeps the kernels at the
//           write bandwidth).
//
// Interleaved vertices (one struct per vertex: position at offset 0, normal at 12, in
// a 24-byte vertex_stride) and separate arrays (one buffer each, or one buffer at
// different offsets) are both packed layouts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "finflex/export.hpp"

namespace finflex {

// The element formats. 4-component formats carry w: 1 for positions, 0 for normals,
// the rest mesh's handedness (+-1) for tangents.
enum class AttributeFormat {
  kFloat32x3,  // 12 bytes
  kFloat32x4,  // 16 bytes
  kFloat16x3,  // 6 bytes, IEEE halves (round to nearest even): normals and tangents
  kFloat16x4,  // 8 bytes: normals and tangents
  kSnorm16x4,  // 8 bytes, round(clamp(c, -1, 1) * 32767) as int16: normals and tangents
  // 4 bytes: a unit vector's octahedral encoding (Cigolle et al. 2014), two snorm16
  // (docs/handoff.md has the GLSL decoding): normals and tangents (no handedness).
  kOctahedral16x2,
};
FINFLEX_API const char* to_string(AttributeFormat format);
FINFLEX_API AttributeFormat parse_attribute_format(const std::string& text,
                                                   const std::string& field = "format");
// Bytes of one element, and of one scalar (its alignment: 4 for float32 and the
// octahedral pair, 2 for the 16-bit formats).
FINFLEX_API std::size_t format_bytes(AttributeFormat format);
FINFLEX_API std::size_t scalar_bytes(AttributeFormat format);

enum class Arrangement { kPlanes, kPacked };
FINFLEX_API const char* to_string(Arrangement arrangement);  // "planes", "packed"
FINFLEX_API Arrangement parse_arrangement(const std::string& text,
                                          const std::string& field = "arrangement");

struct FINFLEX_API AttributeLayout {
  AttributeFormat format = AttributeFormat::kFloat32x3;
  Arrangement arrangement = Arrangement::kPlanes;
  std::size_t offset = 0;           // bytes
  std::size_t vertex_stride = 0;    // packed: bytes from a vertex to the next
  std::size_t plane_stride = 0;     // planes: elements in a plane (>= the vertices)
  std::size_t instance_stride = 0;  // bytes from an instance to the next

  // FinFlex's planes, one instance's three planes after the other's.
  static AttributeLayout planes(AttributeFormat format, std::size_t plane_stride,
                                std::size_t offset = 0);
  // Packed elements; vertex_stride 0 means tightly packed (format_bytes), and
  // instance_stride 0 means the instance's vertices tightly after each other.
  static AttributeLayout packed(AttributeFormat format, std::size_t vertices,
                                std::size_t vertex_stride = 0, std::size_t offset = 0,
                                std::size_t instance_stride = 0);
};

inline bool operator==(const AttributeLayout& a, const AttributeLayout& b) {
  return a.format == b.format && a.arrangement == b.arrangement && a.offset == b.offset &&
         a.vertex_stride == b.vertex_stride && a.plane_stride == b.plane_stride &&
         a.instance_stride == b.instance_stride;
}
inline bool operator!=(const AttributeLayout& a, const AttributeLayout& b) { return !(a == b); }

// Which vertex index the outputs use: the deformer's slots (a rig reorders vertices so
// each component is contiguous, with padding: draw with ClDeformer::remapped_indices();
// the fastest) or the mesh's own order (draw with the mesh's index buffer; padding
// slots are not written).
enum class VertexOrder { kSlots, kMesh };
FINFLEX_API const char* to_string(VertexOrder order);  // "slots", "mesh"
FINFLEX_API VertexOrder parse_vertex_order(const std::string& text,
                                           const std::string& field = "order");

struct FINFLEX_API OutputLayout {
  VertexOrder order = VertexOrder::kSlots;
  AttributeLayout positions;  // kFloat32x3 or kFloat32x4
  AttributeLayout normals;
  // Written when set: the mesh's tangents (the mesh must have them), and each frame's
  // positions before it (motion vectors; kFloat32x3 or kFloat32x4).
  std::optional<AttributeLayout> tangents;
  std::optional<AttributeLayout> previous_positions;

  // Every attribute in the kernels' order (positions, normals, tangents, previous
  // positions), null where it is not written.
  std::array<const AttributeLayout*, 4> written() const {
    return {&positions, &normals, tangents ? &*tangents : nullptr,
            previous_positions ? &*previous_positions : nullptr};
  }
  // The bytes each vertex and instance writes: every written attribute's element.
  std::size_t bytes_per_vertex() const {
    std::size_t bytes = 0;
    for (const AttributeLayout* a : written()) bytes += a ? format_bytes(a->format) : 0;
    return bytes;
  }

  // The bytes a buffer needs to hold `attribute` for `instances` instances of
  // `vertices` vertices (slots or mesh vertices, as `order` says): the end of its last
  // element. Written once, used by every check.
  static std::size_t required_bytes(const AttributeLayout& attribute, std::size_t instances,
                                    std::size_t vertices);
};

inline bool operator==(const OutputLayout& a, const OutputLayout& b) {
  return a.order == b.order && a.positions == b.positions && a.normals == b.normals &&
         a.tangents == b.tangents && a.previous_positions == b.previous_positions;
}
inline bool operator!=(const OutputLayout& a, const OutputLayout& b) { return !(a == b); }

// Checks `layout` for `instances` instances of `vertices` vertices: every attribute's
// format allowed for it, offsets and strides multiples of the format's scalar, strides
// wide enough that no two elements overlap (an instance after another, or a vertex's
// instances side by side), and no two attributes of one buffer sharing a byte (pass
// each attribute's buffer identity in `buffer_ids`: positions, normals, tangents,
// previous; equal ids mean one buffer). kInvalidArgument naming the attribute and the
// rule ("outputs.normals.vertex_stride: 8 bytes is less than a kFloat32x3 element (12)").
FINFLEX_API void validate_output_layout(const OutputLayout& layout, std::size_t instances,
                                        std::size_t vertices,
                                        const std::uintptr_t buffer_ids[4] = nullptr);

}  // namespace finflex

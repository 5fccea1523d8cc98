// Where a batch of deformed instances lives: structure-of-arrays planes.
//
// Every attribute (positions, normals, tangents) is one array of
// instance_count * 3 planes; plane (i, c) holds component c (x, y or z) of instance i
// for every vertex slot, `plane_stride` elements long (the slots rounded up so that
// every plane starts aligned; the padding is written but means nothing):
//
//   positions: | i0.x[0..S) pad | i0.y[0..S) pad | i0.z[0..S) pad | i1.x ... |
//   element (instance i, component c, slot s) = data[(i * 3 + c) * plane_stride + s]
//
// A slot is a vertex of the mesh: the OpenCL backend reorders a rig's vertices so that
// every component is a contiguous range of slots (ClDeformer::slot_of_vertex() maps a
// mesh vertex to its slot; a one-component rig keeps the mesh's order). The CPU
// reference keeps the mesh's order.
//
// Separate x/y/z planes let every work-item write whole cache lines together with its
// neighbours, which is what keeps the kernels at the memory write bandwidth.
// Tangent handedness (w) does not change under the bend: it stays that of the rest mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/export.hpp"

namespace finflex {

// How normals and tangents are stored on the device. Positions are always float32.
//   kFloat32: 4 bytes a component: 24 bytes per vertex with positions (36 with tangents)
//   kHalf:    IEEE half, 2 bytes a component (vstore_half): 18 bytes per vertex (24);
//             relative error 2^-11 (5e-4), ample for shading unit vectors.
enum class NormalFormat { kFloat32, kHalf };
FINFLEX_API const char* to_string(NormalFormat format);
FINFLEX_API NormalFormat parse_normal_format(const std::string& text,
                                             const std::string& field = "normal_format");

// A batch's counts and the shape of its planes: what a host copy (DeformedBatch) holds,
// and what a device batch (DeviceBatch) was made for. Where a device batch's outputs go
// is its OutputLayout (finflex/output_layout.hpp).
struct BatchShape {
  std::size_t vertex_count = 0;  // the mesh's vertices (slots may be more, with padding)
  std::size_t instance_count = 0;
  std::size_t plane_stride = 0;  // >= vertex_count, in elements
  bool tangents = false;
  NormalFormat normal_format = NormalFormat::kFloat32;  // normals and tangents

  // Elements of one attribute array: instance_count * 3 * plane_stride.
  std::size_t attribute_elements() const { return instance_count * 3 * plane_stride; }
  // Bytes of a normal or tangent component on the device.
  std::size_t normal_component_bytes() const {
    return normal_format == NormalFormat::kHalf ? 2 : 4;
  }
  // Bytes written per vertex and instance: positions, normals (and tangents).
  std::size_t bytes_per_vertex() const {
    return 12 + (tangents ? 6 : 3) * normal_component_bytes();
  }
  std::size_t index(std::size_t instance, int component, std::size_t vertex) const {
    return (instance * 3 + static_cast<std::size_t>(component)) * plane_stride + vertex;
  }
};

// Rounds vertex_count up to the plane alignment FinFlex uses (64 elements).
FINFLEX_API std::size_t padded_plane_stride(std::size_t vertex_count);

// A batch on the host, in float (from a device) or double (from the reference).
// Accessors take the mesh's own vertex index: where the engine reordered vertices
// (rigs: each component a contiguous range of slots), slot_of_vertex maps it.
template <typename T>
struct DeformedBatch {
  using Vec3 = glm::vec<3, T, glm::defaultp>;

  BatchShape shape;
  std::vector<T> positions;
  std::vector<T> normals;
  std::vector<T> tangents;                    // empty unless shape.tangents
  std::vector<T> previous_positions;          // empty unless the batch writes them
  std::vector<std::uint32_t> slot_of_vertex;  // empty: slot = vertex

  Vec3 position(std::size_t instance, std::size_t vertex) const {
    return gather(positions, instance, vertex);
  }
  Vec3 normal(std::size_t instance, std::size_t vertex) const {
    return gather(normals, instance, vertex);
  }
  Vec3 tangent(std::size_t instance, std::size_t vertex) const {
    return gather(tangents, instance, vertex);
  }
  Vec3 previous_position(std::size_t instance, std::size_t vertex) const {
    return gather(previous_positions, instance, vertex);
  }

  void resize(const BatchShape& new_shape) {
    shape = new_shape;
    positions.assign(shape.attribute_elements(), T(0));
    normals.assign(shape.attribute_elements(), T(0));
    tangents.assign(shape.tangents ? shape.attribute_elements() : 0, T(0));
  }
  void scatter(std::vector<T>& data, std::size_t instance, std::size_t vertex, const Vec3& value) {
    for (int c = 0; c < 3; ++c) data[shape.index(instance, c, vertex)] = value[c];
  }

 private:
  Vec3 gather(const std::vector<T>& data, std::size_t instance, std::size_t vertex) const {
    const std::size_t slot = slot_of_vertex.empty() ? vertex : slot_of_vertex[vertex];
    return Vec3(data[shape.index(instance, 0, slot)], data[shape.index(instance, 1, slot)],
                data[shape.index(instance, 2, slot)]);
  }
};

}  // namespace finflex

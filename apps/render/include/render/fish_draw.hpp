// Fish to draw: instances of one mesh (a species), with their own deformed positions
// and normals, read by the vertex shader from buffers the caller describes.
//
// A stream holds element (instance i, component c, vertex v) at byte
//
//   offset + i * instance_stride + v * vertex_stride + c * component_stride
//
// so one descriptor serves FinFlex's structure-of-arrays planes and interleaved xyz.
// With E the bytes of an element (4 for float32, 2 for half):
//
//   planes (finflex/batch.hpp), plane_stride P elements:
//     | i0.x[0..V) pad | i0.y[0..V) pad | i0.z[0..V) pad | i1.x ... |
//     component_stride = P E, vertex_stride = E, instance_stride = 3 P E
//   interleaved, V vertices an instance:
//     | i0: x y z | x y z | ... | i1: x y z | ...
//     component_stride = E, vertex_stride = 3 E, instance_stride = 3 V E
//
// A stream of N instances of V vertices needs bytes up to its last element:
//   offset + (N - 1) instance_stride + (V - 1) vertex_stride + 2 component_stride + E.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

namespace finflex::render {

enum class ComponentType {
  kFloat32,  // IEEE float
  kFloat16,  // IEEE half (FinFlex's NormalFormat::kHalf normals)
};

struct StreamLayout {
  std::size_t offset = 0;  // bytes, all five
  std::size_t instance_stride = 0;
  std::size_t vertex_stride = 0;
  std::size_t component_stride = 0;
  ComponentType type = ComponentType::kFloat32;

  // FinFlex's planes: plane_stride in elements (DeviceBatch::layout.plane_stride).
  static StreamLayout planes(std::size_t plane_stride,
                             ComponentType type = ComponentType::kFloat32);
  // x y z per vertex, vertex_count vertices per instance, instances one after another.
  static StreamLayout interleaved(std::size_t vertex_count,
                                  ComponentType type = ComponentType::kFloat32);

  std::size_t element_bytes() const { return type == ComponentType::kFloat16 ? 2 : 4; }
  // Bytes from the start of the buffer to the end of the last element (formula above).
  std::size_t required_bytes(std::size_t instances, std::size_t vertices) const;
};

// Handles the renderer gives out: valid for the renderer that made them.
using MeshId = std::size_t;
using BufferId = std::size_t;
constexpr BufferId kNoBuffer = static_cast<BufferId>(-1);

// Where a stream's bytes are: host memory, copied into a GL buffer of the renderer
// when the frame is drawn (kept alive only during Renderer::render), or a buffer of
// the renderer (Renderer::create_buffer; e.g. written by OpenCL through GL sharing),
// read in place. Exactly one of the two.
struct VertexStream {
  const void* host = nullptr;
  std::size_t host_bytes = 0;
  BufferId buffer = kNoBuffer;
  StreamLayout layout;

  static VertexStream from_host(const void* data, std::size_t bytes, const StreamLayout& layout);
  static VertexStream from_buffer(BufferId buffer, const StreamLayout& layout);
};

// Which instances a draw draws, decided on the GPU: a buffer of the renderer (e.g.
// memory that FinFlex's LevelChooser fills each frame through ExternalOutputs' side
// copies) holds, at command_offset, GL's DrawElementsIndirectCommand
//   {count, instanceCount, firstIndex, baseVertex, baseInstance}   (5 uint32)
// and, at entries_offset, one uint32 per drawn instance: its entry in FishDraw::ids.
// Drawn instance i reads row i of the streams; instanceCount must not exceed the
// draw's instance_count (the rows), count + firstIndex the mesh's indices, and
// baseVertex and baseInstance are 0: the renderer cannot check what the GPU reads.
struct DeviceList {
  BufferId buffer = kNoBuffer;     // kNoBuffer: the host's instance_count instances
  std::size_t command_offset = 0;  // bytes, a multiple of 4
  std::size_t entries_offset = 0;  // bytes, a multiple of 4
};

struct FishDraw {
  MeshId mesh = 0;                      // Renderer::add_mesh: the triangles, shared
  glm::vec3 albedo{0.8f, 0.45f, 0.2f};  // the species' colour, linear RGB in 0..1
  std::size_t instance_count = 0;       // 0 draws nothing; with a list, the rows it may draw
  DeviceList list;                      // the GPU's instances (Renderer::draws_device_lists)
  VertexStream positions;               // mesh coordinates, one set per instance
  VertexStream normals;                 // unit vectors (normalised again when shading)
  // Per instance, world from mesh coordinates: a rotation, a uniform scale and a
  // translation (normals go through the upper 3x3 and are normalised). nullptr: the
  // identity (positions are world coordinates). Else instance_count matrices, read
  // during Renderer::render only.
  const glm::mat4* transforms = nullptr;
  // Per instance, the value the id pass writes where the instance is the nearest
  // surface (Renderer::render_ids; 0 is the background, so ids are > 0). Needed by
  // render_ids only; instance_count values, read during that call. With a list, the
  // table its entries index: id_count values.
  const std::uint32_t* ids = nullptr;
  std::size_t id_count = 0;  // with a list: the entries of ids
};

}  // namespace finflex::render

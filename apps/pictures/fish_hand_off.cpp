#include "fish_hand_off.hpp"

#include <string>

namespace finflex::pictures {

namespace {

std::size_t position_bytes(const BatchLayout& layout) {
  return layout.attribute_elements() * sizeof(float);
}

std::size_t normal_bytes(const BatchLayout& layout) {
  return layout.attribute_elements() * layout.normal_component_bytes();
}

// Maps `buffer` for reading (blocking: the commands before it finish first), copies
// its first `bytes` into the renderer's `target` and unmaps it.
void copy_through_host(cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes,
                       render::Renderer& renderer, render::BufferId target) {
  cl_int status = CL_SUCCESS;
  void* mapped =
      queue.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes, nullptr, nullptr, &status);
  if (status != CL_SUCCESS || mapped == nullptr) {
    throw Error(ErrorCode::kOpenCL, "hand_off",
                "mapping a deformed batch for the renderer failed (OpenCL error " +
                    std::to_string(status) + ")");
  }
  try {
    renderer.write_buffer(target, 0, mapped, bytes);
  } catch (...) {
    queue.enqueueUnmapMemObject(buffer, mapped);
    throw;
  }
  queue.enqueueUnmapMemObject(buffer, mapped);
}

}  // namespace

SpeciesDrawing prepare_drawing(render::Renderer& renderer, const ClDeformer& deformer,
                               const DeviceBatch& batch, const glm::vec3& albedo,
                               std::vector<std::uint32_t> ids) {
  const BatchLayout& layout = batch.layout;
  SpeciesDrawing drawing;
  // The triangles over slots; padding slots (never indexed) are vertices too.
  drawing.mesh = renderer.add_mesh(deformer.remapped_indices(), layout.plane_stride);
  drawing.positions = renderer.create_buffer(position_bytes(layout));
  drawing.normals = renderer.create_buffer(normal_bytes(layout));
  drawing.position_layout = render::StreamLayout::planes(layout.plane_stride);
  drawing.normal_layout =
      render::StreamLayout::planes(layout.plane_stride, layout.normal_format == NormalFormat::kHalf
                                                            ? render::ComponentType::kFloat16
                                                            : render::ComponentType::kFloat32);
  drawing.instance_count = layout.instance_count;
  drawing.albedo = albedo;
  drawing.ids = std::move(ids);
  return drawing;
}

render::FishDraw hand_off(cl::CommandQueue& queue, const DeviceBatch& batch,
                          render::Renderer& renderer, const SpeciesDrawing& drawing) {
  copy_through_host(queue, batch.positions, position_bytes(batch.layout), renderer,
                    drawing.positions);
  copy_through_host(queue, batch.normals, normal_bytes(batch.layout), renderer, drawing.normals);
  render::FishDraw draw;
  draw.mesh = drawing.mesh;
  draw.albedo = drawing.albedo;
  draw.instance_count = drawing.instance_count;
  draw.positions = render::VertexStream::from_buffer(drawing.positions, drawing.position_layout);
  draw.normals = render::VertexStream::from_buffer(drawing.normals, drawing.normal_layout);
  draw.ids = drawing.ids.data();
  return draw;
}

}  // namespace finflex::pictures

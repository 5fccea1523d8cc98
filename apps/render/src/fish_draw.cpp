#include "render/fish_draw.hpp"

namespace finflex::render {

StreamLayout StreamLayout::planes(std::size_t plane_stride, ComponentType type) {
  StreamLayout layout;
  layout.type = type;
  const std::size_t plane_bytes = plane_stride * layout.element_bytes();
  layout.vertex_stride = layout.element_bytes();
  layout.component_stride = plane_bytes;
  layout.instance_stride = 3 * plane_bytes;
  return layout;
}

StreamLayout StreamLayout::interleaved(std::size_t vertex_count, ComponentType type) {
  StreamLayout layout;
  layout.type = type;
  layout.component_stride = layout.element_bytes();
  layout.vertex_stride = 3 * layout.element_bytes();
  layout.instance_stride = vertex_count * layout.vertex_stride;
  return layout;
}

std::size_t StreamLayout::required_bytes(std::size_t instances, std::size_t vertices) const {
  if (instances == 0 || vertices == 0) return 0;
  return offset + (instances - 1) * instance_stride + (vertices - 1) * vertex_stride +
         2 * component_stride + element_bytes();
}

VertexStream VertexStream::from_host(const void* data, std::size_t bytes,
                                     const StreamLayout& layout) {
  VertexStream stream;
  stream.host = data;
  stream.host_bytes = bytes;
  stream.layout = layout;
  return stream;
}

VertexStream VertexStream::from_buffer(BufferId buffer, const StreamLayout& layout) {
  VertexStream stream;
  stream.buffer = buffer;
  stream.layout = layout;
  return stream;
}

}  // namespace finflex::render

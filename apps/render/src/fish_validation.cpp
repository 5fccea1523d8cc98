#include "fish_validation.hpp"

#include <string>

#include "checks.hpp"

namespace finflex::render::detail {

namespace {

void validate_stream(const std::string& field, const VertexStream& stream, std::size_t instances,
                     std::size_t vertices, const std::vector<BufferResource>& buffers) {
  const bool host = stream.host != nullptr;
  const bool device = stream.buffer != kNoBuffer;
  if (host == device) {
    invalid(field, host ? "has both host data and a buffer" : "has neither host data nor a buffer");
  }
  const StreamLayout& layout = stream.layout;
  const std::size_t element = layout.element_bytes();
  const std::pair<const char*, std::size_t> sizes[] = {
      {"offset", layout.offset},
      {"instance_stride", layout.instance_stride},
      {"vertex_stride", layout.vertex_stride},
      {"component_stride", layout.component_stride}};
  for (const auto& [name, value] : sizes) {
    if (value % element != 0) {
      invalid(field + ".layout." + name, std::to_string(value) + " is not a multiple of " +
                                             std::to_string(element) + " bytes (the element)");
    }
  }
  if (layout.vertex_stride == 0 && vertices > 1) {
    invalid(field + ".layout.vertex_stride", "0 (every vertex would read the same element)");
  }
  std::size_t available = stream.host_bytes;
  if (device) {
    if (stream.buffer >= buffers.size()) {
      invalid(field + ".buffer",
              std::to_string(stream.buffer) + " is not a buffer of this renderer");
    }
    available = buffers[stream.buffer].bytes;
  }
  const std::size_t needed = layout.required_bytes(instances, vertices);
  if (available < needed) {
    invalid(field, std::to_string(available) + " bytes, but " + std::to_string(instances) +
                       " instances of " + std::to_string(vertices) + " vertices need " +
                       std::to_string(needed));
  }
}

}  // namespace

void validate_fish(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
                   const std::vector<BufferResource>& buffers) {
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& draw = fish[d];
    const std::string field = "fish[" + std::to_string(d) + "]";
    if (draw.instance_count == 0) continue;
    if (draw.mesh >= meshes.size()) {
      invalid(field + ".mesh", std::to_string(draw.mesh) + " is not a mesh of this renderer");
    }
    const std::size_t vertices = meshes[draw.mesh].vertex_count;
    require_non_negative(field + ".albedo", draw.albedo);
    for (int c = 0; c < 3; ++c) {
      if (draw.albedo[c] > 1.0f) invalid(field + ".albedo", to_text(draw.albedo) + " is above 1");
    }
    validate_stream(field + ".positions", draw.positions, draw.instance_count, vertices, buffers);
    validate_stream(field + ".normals", draw.normals, draw.instance_count, vertices, buffers);
  }
}

void validate_ids(const std::vector<FishDraw>& fish) {
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& draw = fish[d];
    if (draw.instance_count == 0) continue;
    const std::string field = "fish[" + std::to_string(d) + "].ids";
    if (draw.ids == nullptr) invalid(field, "is null: the id pass needs an id per instance");
    for (std::size_t i = 0; i < draw.instance_count; ++i) {
      if (draw.ids[i] == 0) {
        invalid(field + "[" + std::to_string(i) + "]", "0 (the background's id; ids are > 0)");
      }
    }
  }
}

}  // namespace finflex::render::detail

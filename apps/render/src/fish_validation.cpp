#include "fish_validation.hpp"

#include <string>
#include <utility>

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

void validate_list(const std::string& field, const DeviceList& list, std::size_t rows,
                   const std::vector<BufferResource>& buffers, bool device_lists) {
  if (!device_lists) {
    invalid(field, "the context has no glDrawElementsIndirect (GL 4.0, ARB_draw_indirect)");
  }
  if (list.buffer >= buffers.size()) {
    invalid(field + ".buffer", std::to_string(list.buffer) + " is not a buffer of this renderer");
  }
  const std::size_t bytes = buffers[list.buffer].bytes;
  const std::pair<const char*, std::size_t> parts[] = {{"command_offset", list.command_offset},
                                                       {"entries_offset", list.entries_offset}};
  for (const auto& [name, offset] : parts) {
    if (offset % 4 != 0)
      invalid(field + "." + name, std::to_string(offset) + " is not a multiple of 4");
  }
  if (list.command_offset > bytes || bytes - list.command_offset < 20) {
    invalid(field + ".command_offset", std::to_string(list.command_offset) +
                                           ": the 20-byte command passes the buffer's " +
                                           std::to_string(bytes) + " bytes");
  }
  if (list.entries_offset > bytes || (bytes - list.entries_offset) / 4 < rows) {
    invalid(field + ".entries_offset", std::to_string(list.entries_offset) + ": " +
                                           std::to_string(rows) + " entries pass the buffer's " +
                                           std::to_string(bytes) + " bytes");
  }
}

}  // namespace

void validate_fish(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
                   const std::vector<BufferResource>& buffers, bool device_lists) {
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
    if (draw.list.buffer != kNoBuffer) {
      validate_list(field + ".list", draw.list, draw.instance_count, buffers, device_lists);
    }
  }
}

void validate_ids(const std::vector<FishDraw>& fish) {
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& draw = fish[d];
    if (draw.instance_count == 0) continue;
    const std::string field = "fish[" + std::to_string(d) + "].ids";
    if (draw.ids == nullptr) invalid(field, "is null: the id pass needs an id per instance");
    const bool listed = draw.list.buffer != kNoBuffer;
    if (listed && draw.id_count == 0) {
      invalid("fish[" + std::to_string(d) + "].id_count", "0: a device list's entries index ids");
    }
    const std::size_t count = listed ? draw.id_count : draw.instance_count;
    for (std::size_t i = 0; i < count; ++i) {
      if (draw.ids[i] == 0) {
        invalid(field + "[" + std::to_string(i) + "]", "0 (the background's id; ids are > 0)");
      }
    }
  }
}

}  // namespace finflex::render::detail

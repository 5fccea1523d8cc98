#include "fish_hand_off.hpp"

#include "landmarks.hpp"

#include <algorithm>
#include <array>
#include <chrono>

namespace finflex::pictures {

namespace {

// A device list's layout in the side region: the command (5 uint32), padded, then
// the entries.
constexpr std::size_t kListEntries = 32;

// FinFlex's planes of positions and normals for the renderer: no tangents (not drawn).
OutputLayout drawn_planes(const ClDeformer& deformer, std::size_t instances, NormalFormat format) {
  OutputLayout layout = deformer.layout(instances, format);
  layout.tangents.reset();
  layout.previous_positions.reset();
  return layout;
}

// Bytes of a GL buffer for `attribute`: what the engine checks, and every plane whole
// (what the renderer's StreamLayout::planes over all the slots reads).
std::size_t buffer_bytes(const ClDeformer& deformer, const AttributeLayout& attribute,
                         std::size_t instances) {
  const std::size_t engine = OutputLayout::required_bytes(
      attribute, instances, deformer.output_vertices(VertexOrder::kSlots));
  return std::max(engine, instances * attribute.instance_stride);
}

render::StreamLayout stream_layout(const AttributeLayout& attribute) {
  return render::StreamLayout::planes(attribute.plane_stride,
                                      attribute.format == AttributeFormat::kFloat16x3
                                          ? render::ComponentType::kFloat16
                                          : render::ComponentType::kFloat32);
}

// Why GL cannot import `device`'s memory (empty: it can).
std::string why_gl_cannot_import(const render::Renderer& renderer, const vulkan::Device& device) {
  const render::ExternalSupport& gl = renderer.external_support();
  if (!gl.memory) return gl.why_not;
  const bool same = std::find(gl.device_uuids.begin(), gl.device_uuids.end(), device.uuid()) !=
                    gl.device_uuids.end();
  if (!same) {
    std::string seen;
    for (const auto& uuid : gl.device_uuids)
      seen += (seen.empty() ? "" : ", ") + vulkan::to_string(uuid);
    return "OpenGL (" + renderer.device().gl_renderer + ") is not on the Vulkan device " +
           device.name() + " (" + vulkan::to_string(device.uuid()) +
           "; GL's: " + (seen.empty() ? "none given" : seen) + ")";
  }
  return "";
}

}  // namespace

const char* to_string(HandOffPath path) {
  switch (path) {
    case HandOffPath::kExternal:
      return "external-memory";
    case HandOffPath::kShared:
      return "shared";
    case HandOffPath::kCopy:
      return "copy";
  }
  return "copy";
}

std::optional<HandOffPath> parse_hand_off(const std::string& text, const std::string& field) {
  if (text == "auto") return std::nullopt;
  for (HandOffPath path : {HandOffPath::kExternal, HandOffPath::kShared, HandOffPath::kCopy}) {
    if (text == to_string(path)) return path;
  }
  throw Error(ErrorCode::kInvalidArgument, field,
              field + ": '" + text + "' is not auto, external-memory, shared or copy");
}

HandOff choose_hand_off(render::Renderer& renderer, const Context& context,
                        const std::string& why_not_shared, std::optional<HandOffPath> wanted) {
  HandOff out;
  const bool shares = why_not_shared.empty();
  if (wanted && *wanted != HandOffPath::kExternal) out.why_not_external = "not asked for";
  if (!wanted || *wanted == HandOffPath::kExternal) {
    ExternalChoice choice = choose_external_device(context);
    if (choice.device) {
      out.why_not_external = why_gl_cannot_import(renderer, *choice.device);
      if (out.why_not_external.empty()) {
        out.path = HandOffPath::kExternal;
        out.import = choice.import;
        out.device = std::move(choice.device);
        return out;
      }
    } else if (out.why_not_external.empty()) {
      out.why_not_external = choice.why_not;
    }
    if (wanted) {
      throw Error(ErrorCode::kDevice, "--hand-off",
                  "--hand-off external-memory: " + out.why_not_external);
    }
  }
  if (!wanted || *wanted == HandOffPath::kShared) {
    if (shares) {
      out.path = HandOffPath::kShared;
      return out;
    }
    out.why_not_shared = why_not_shared;
    if (wanted)
      throw Error(ErrorCode::kDevice, "--hand-off", "--hand-off shared: " + why_not_shared);
  } else {
    out.why_not_shared = "not asked for";
  }
  out.path = HandOffPath::kCopy;
  return out;
}

GlSpeciesOutputs::GlSpeciesOutputs(render::Renderer& renderer, const HandOff& hand_off,
                                   ClDeformer& deformer, std::size_t instances, NormalFormat format)
    : renderer_(renderer),
      path_(hand_off.path),
      layout_(drawn_planes(deformer, instances, format)),
      position_layout_(stream_layout(layout_.positions)),
      normal_layout_(stream_layout(layout_.normals)),
      instances_(instances) {
  if (path_ == HandOffPath::kExternal) {
    sets_.push_back(make_set(hand_off, deformer));
    const ExternalOutputs& first = *sets_.front().outputs;
    device_ordered_ = first.device_ordered() && renderer.external_support().semaphores;
    if (!first.device_ordered()) {
      why_not_ordered_ = first.semaphores_why_not();
    } else if (!renderer.external_support().semaphores) {
      why_not_ordered_ = "OpenGL has no GL_EXT_semaphore_fd";
    }
    if (device_ordered_) sets_.push_back(make_set(hand_off, deformer));
    return;
  }
  positions_ = renderer.create_buffer(buffer_bytes(deformer, layout_.positions, instances));
  normals_ = renderer.create_buffer(buffer_bytes(deformer, layout_.normals, instances));
  // create_buffer left the renderer's context current, as GlOutputs needs.
  gl_ = std::make_unique<GlOutputs>(
      deformer, instances, layout_,
      GlBuffers{renderer.gl_buffer(positions_), renderer.gl_buffer(normals_), 0, 0});
}

GlSpeciesOutputs::ExternalSet GlSpeciesOutputs::make_set(const HandOff& hand_off,
                                                         ClDeformer& deformer) {
  ExternalSet set;
  set.outputs = std::make_unique<ExternalOutputs>(deformer, instances_, layout_, *hand_off.device,
                                                  std::array<std::size_t, 4>{0, 1, 2, 3}, 256,
                                                  kListEntries + 4 * instances_);
  const ExternalOutputs& outputs = *set.outputs;
  std::vector<render::BufferId> imported;
  for (std::size_t b = 0; b < outputs.buffer_count(); ++b) {
    const vulkan::ExternalBuffer& buffer = outputs.buffer(b);
    const std::size_t bytes =
        b == 0 ? outputs.side_offset() + outputs.side_bytes() : outputs.data_bytes(b);
    imported.push_back(renderer_.import_buffer(buffer.export_fd(), buffer.memory_bytes(), bytes));
  }
  set.side = imported[0];
  set.positions = imported[outputs.buffer_of(0)];
  set.normals = imported[outputs.buffer_of(1)];
  if (outputs.device_ordered() && renderer_.external_support().semaphores) {
    set.kernels_done = renderer_.import_semaphore(outputs.kernels_done()->export_fd());
    set.drawn = renderer_.import_semaphore(outputs.consumer_done()->export_fd());
  }
  return set;
}

void GlSpeciesOutputs::set_list_sources(const cl::Buffer& command, std::size_t command_offset,
                                        const cl::Buffer& entries, std::size_t entries_offset,
                                        std::size_t rows) {
  if (sets_.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "list",
                std::string("list: the ") + to_string(path_) + " hand-off has no device list");
  }
  if (rows > instances_) {
    throw Error(ErrorCode::kInvalidArgument, "rows",
                "rows: " + std::to_string(rows) + " is more than the outputs' " +
                    std::to_string(instances_) + " instances");
  }
  list_copies_ = {{&command, command_offset, 5 * sizeof(std::uint32_t), 0},
                  {&entries, entries_offset, rows * sizeof(std::uint32_t), kListEntries}};
}

render::DeviceList GlSpeciesOutputs::device_list() const {
  render::DeviceList list;
  if (sets_.empty()) return list;
  const ExternalSet& set = sets_[current_];
  list.buffer = set.side;
  list.command_offset = set.outputs->side_offset();
  list.entries_offset = set.outputs->side_offset() + kListEntries;
  return list;
}

render::BufferId GlSpeciesOutputs::positions() const {
  return sets_.empty() ? positions_ : sets_[current_].positions;
}

render::BufferId GlSpeciesOutputs::normals() const {
  return sets_.empty() ? normals_ : sets_[current_].normals;
}

DeviceBatch& GlSpeciesOutputs::batch() {
  return sets_.empty() ? gl_->batch() : sets_[current_].outputs->batch();
}

double GlSpeciesOutputs::handoff_seconds() const {
  return gl_ ? gl_->last_handoff_seconds() : 0.0;  // external memory: nothing to hand over
}

void GlSpeciesOutputs::signal_drawn(ExternalSet& set) {
  renderer_.signal_semaphore(set.drawn, {set.positions, set.normals});
  set.outputs->consumer_signalled();
  set.gl_used = false;
}

cl::Event GlSpeciesOutputs::enqueue(ClDeformer& /*deformer: the outputs'*/, const ClJob& job,
                                    std::vector<cl::Event>* kernel_events) {
  renderer_.make_current();
  if (sets_.empty()) {
    drawable_ = gl_->enqueue(job, kernel_events);
    return drawable_;
  }
  const std::size_t next = frames_ == 0 ? 0 : (current_ + 1) % sets_.size();
  ExternalSet& set = sets_[next];
  ClJob into = job;
  into.outputs = &set.outputs->batch();
  if (device_ordered_) {
    // GL is done with the last frame once the commands so far are in: its signal now.
    if (sets_[current_].gl_used) signal_drawn(sets_[current_]);
    // A binary semaphore is waited for once per signal: a frame of this set that GL
    // never drew is waited for now, and GL's signal after it lets the kernels go on.
    if (set.kernels_signalled) {
      renderer_.wait_semaphore(set.kernels_done, {set.positions, set.normals});
      set.kernels_signalled = false;
      signal_drawn(set);
    }
    drawable_ = set.outputs->enqueue(into, kernel_events, list_copies_);
    set.kernels_signalled = true;
  } else {
    renderer_.finish();  // GL is done with the memory the kernels now write
    drawable_ = set.outputs->enqueue(into, kernel_events, list_copies_);
  }
  current_ = next;
  ++frames_;
  return drawable_;
}

void GlSpeciesOutputs::wait_until_drawable() {
  if (sets_.empty()) {
    if (drawable_() != nullptr) check_cl(drawable_.wait(), "clWaitForEvents");
    return;
  }
  ExternalSet& set = sets_[current_];
  if (!device_ordered_) {
    set.outputs->wait_for_frame();
    return;
  }
  if (!set.kernels_signalled) return;
  renderer_.wait_semaphore(set.kernels_done, {set.positions, set.normals});
  set.kernels_signalled = false;
  set.gl_used = true;
}

void GlSpeciesOutputs::begin_reading() {
  renderer_.make_current();
  if (!sets_.empty()) {
    sets_[current_].outputs->begin_reading();  // GL only reads the memory too: no wait for it
    return;
  }
  gl_->begin_reading();
}

void GlSpeciesOutputs::end_reading() {
  if (!sets_.empty()) {
    sets_[current_].outputs->end_reading();
    return;
  }
  gl_->end_reading();
}

tank::OutputsFactory gl_outputs(render::Renderer& renderer, const HandOff& hand_off) {
  return [&renderer, &hand_off](std::size_t, ClDeformer& deformer, std::size_t instances,
                                NormalFormat format) -> std::unique_ptr<tank::SpeciesOutputs> {
    return std::make_unique<GlSpeciesOutputs>(renderer, hand_off, deformer, instances, format);
  };
}

SpeciesDrawing prepare_drawing(render::Renderer& renderer, const ClDeformer& deformer,
                               GlSpeciesOutputs& outputs, const glm::vec3& albedo,
                               std::vector<std::uint32_t> ids) {
  SpeciesDrawing drawing;
  // The triangles over slots; padding slots (never indexed) are vertices too, and so
  // is each vertex's place on the body, painted by the colour pass.
  const std::size_t slots = outputs.layout().positions.plane_stride;
  const std::vector<glm::vec2> body = body_pattern(deformer.model());
  const std::vector<std::uint32_t>& slot_of = deformer.slot_of_vertex();
  std::vector<glm::vec2> pattern(slots, glm::vec2(0.5f, 0.0f));
  for (std::size_t v = 0; v < body.size() && v < slot_of.size(); ++v) {
    if (slot_of[v] < slots) pattern[slot_of[v]] = body[v];
  }
  drawing.mesh = renderer.add_mesh(deformer.remapped_indices(), slots, pattern);
  drawing.outputs = &outputs;
  drawing.albedo = albedo;
  drawing.ids = std::move(ids);
  return drawing;
}

render::FishDraw fish_draw(const SpeciesDrawing& drawing) {
  render::FishDraw draw;
  draw.mesh = drawing.mesh;
  draw.albedo = drawing.albedo;
  draw.instance_count = drawing.outputs->instance_count();
  draw.ids = drawing.ids.data();
  point_at_last_frame(drawing, draw);
  return draw;
}

void point_at_last_frame(const SpeciesDrawing& drawing, render::FishDraw& draw) {
  const GlSpeciesOutputs& outputs = *drawing.outputs;
  draw.positions =
      render::VertexStream::from_buffer(outputs.positions(), outputs.position_layout());
  draw.normals = render::VertexStream::from_buffer(outputs.normals(), outputs.normal_layout());
  if (draw.list.buffer != render::kNoBuffer) draw.list = outputs.device_list();
}

}  // namespace finflex::pictures

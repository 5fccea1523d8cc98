// Where the renderer gets the engine's deformed fish: each species' deformation writes
// buffers that the renderer draws as they are. This is the one point of hand-off
// between the engine and the renderer.
//
// The buffers hold FinFlex's planes (ClDeformer::layout: positions, normals; no
// tangents, which the renderer does not draw) over the deformer's slots, in world
// space (the tank's placements are the deformation's last stage), so they are drawn
// with StreamLayout::planes over remapped_indices() and no transform. Three paths,
// the first that can run is taken (choose_hand_off), and the summary says why the
// ones before it could not:
//  - external memory (finflex/external_outputs.hpp): the buffers live in Vulkan
//    memory of the OpenCL device (matched by UUID), imported by OpenCL and by GL
//    (GL_EXT_memory_object_fd). With semaphores on both sides (NVIDIA) the frame
//    orders itself on the GPU: GL waits for the kernels' semaphore before drawing and
//    signals its own once it has drawn, and the kernels that next write those buffers
//    wait for it. Two sets of buffers, alternate frames: frame f + 1's kernels write
//    one set while GL still draws frame f from the other, so neither the host nor the
//    GPU waits for the draw before the next deformation (NVIDIA's semaphore wait
//    blocks the host until it is signalled). A CPU device (PoCL) writes the memory
//    through its host mapping (Mesa's lavapipe and llvmpipe share it), one set,
//    waited for on the host.
//  - shared (cl_khr_gl_sharing): the kernels write the GL buffers between an acquire
//    and a release (GlOutputs).
//  - copy: the kernels write a device mirror of each GL buffer, mapped for reading and
//    uploaded with glBufferSubData every frame (GlOutputs).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/external_outputs.hpp"
#include "finflex/finflex.hpp"
#include "finflex/gl_outputs.hpp"
#include "render/renderer.hpp"
#include "swim_scene.hpp"

namespace finflex::pictures {

enum class HandOffPath { kExternal, kShared, kCopy };
const char* to_string(HandOffPath path);  // "external-memory", "shared", "copy"
// "auto" (the first that can run), or a path's name: kInvalidArgument naming `field`.
std::optional<HandOffPath> parse_hand_off(const std::string& text, const std::string& field);

// The path of a run, chosen once: the Vulkan device of the external path, and why each
// path before the chosen one could not run.
struct HandOff {
  HandOffPath path = HandOffPath::kCopy;
  std::unique_ptr<vulkan::Device> device;  // kExternal
  ExternalImport import = ExternalImport::kImported;
  std::string why_not_external;
  std::string why_not_shared;
};

// The first path of external memory, sharing (`why_not_shared`: GlSharingContext's
// why_not from make_gl_sharing_context, empty when `context` shares the renderer's GL
// context) and copy that can run; `wanted` (not auto) takes that path or fails with kDevice naming
// why not.
HandOff choose_hand_off(render::Renderer& renderer, const Context& context,
                        const std::string& why_not_shared,
                        std::optional<HandOffPath> wanted = std::nullopt);

// One species' outputs: buffers of `renderer` holding `instances` instances of the
// deformer's model in FinFlex's planes (normals in `format`), on `hand_off`'s path.
// Errors: as ExternalOutputs, GlOutputs and Renderer::create_buffer / import_buffer.
class GlSpeciesOutputs : public tank::SpeciesOutputs {
 public:
  GlSpeciesOutputs(render::Renderer& renderer, const HandOff& hand_off, ClDeformer& deformer,
                   std::size_t instances, NormalFormat format);

  DeviceBatch& batch() override;
  // The frame's hand-off with the renderer's context current; external memory with
  // semaphores first lets GL signal that it is done with the last frame.
  cl::Event enqueue(ClDeformer& deformer, const ClJob& job,
                    std::vector<cl::Event>* kernel_events) override;
  double handoff_seconds() const override;
  // The copy path waits for the frame's kernels before copying to GL; external memory
  // imported by OpenCL takes the frame's gate open first, since the driver may wait on
  // the host for the commands before its semaphore calls.
  bool waits_for_device() const override {
    return path_ == HandOffPath::kCopy ||
           (!sets_.empty() && sets_.front().outputs->import() == ExternalImport::kImported);
  }
  void begin_reading() override;
  void end_reading() override;

  HandOffPath path() const { return path_; }
  // External memory: beside the outputs, room for a draw list of instance_count() rows
  // (its command and entries, filled each frame by OpenCL copies ordered as the
  // outputs are: device_list() is what the renderer reads). Elsewhere none.
  bool has_device_list() const { return !sets_.empty(); }
  // Each frame's copies: the 20-byte command at `command` + command_offset, and
  // `rows` (at most instance_count()) entries at `entries` + entries_offset.
  void set_list_sources(const cl::Buffer& command, std::size_t command_offset,
                        const cl::Buffer& entries, std::size_t entries_offset, std::size_t rows);
  // The last frame's list (external memory: its set of buffers).
  render::DeviceList device_list() const;
  // External memory: the sets of buffers that frames take in turn (2 where semaphores
  // order the frames, else 1); 0 on the other paths.
  std::size_t buffer_sets() const { return sets_.size(); }
  // External memory: whether semaphores order the frame on the GPU, and why not.
  bool device_ordered() const { return device_ordered_; }
  const std::string& why_not_device_ordered() const { return why_not_ordered_; }
  // Makes GL's next commands wait until the last frame enqueued is in the buffers: a
  // GPU-side wait (semaphores), else a host wait (the release event, the CPU's map).
  void wait_until_drawable();

  const OutputLayout& layout() const { return layout_; }
  // The buffers of the last frame enqueued (external memory: its set).
  render::BufferId positions() const;
  render::BufferId normals() const;
  const render::StreamLayout& position_layout() const { return position_layout_; }
  const render::StreamLayout& normal_layout() const { return normal_layout_; }
  std::size_t instance_count() const { return instances_; }

 private:
  // External memory: one set of buffers, GL's imports of them and of the semaphores,
  // and where the set stands.
  struct ExternalSet {
    std::unique_ptr<ExternalOutputs> outputs;
    render::BufferId side = render::kNoBuffer;  // buffer 0, with the list
    render::BufferId positions = render::kNoBuffer;
    render::BufferId normals = render::kNoBuffer;
    render::SemaphoreId kernels_done = 0;  // with semaphores
    render::SemaphoreId drawn = 0;
    bool kernels_signalled = false;  // by its last frame's kernels, not yet waited for by GL
    bool gl_used = false;            // GL has waited for its frame: its drawn signal is owed
  };
  ExternalSet make_set(const HandOff& hand_off, ClDeformer& deformer);
  // GL signals `set`'s semaphore after its commands so far (they read its last frame).
  void signal_drawn(ExternalSet& set);

  render::Renderer& renderer_;
  HandOffPath path_;
  OutputLayout layout_;
  render::BufferId positions_ = render::kNoBuffer;  // kShared, kCopy
  render::BufferId normals_ = render::kNoBuffer;
  render::StreamLayout position_layout_;
  render::StreamLayout normal_layout_;
  std::size_t instances_ = 0;
  std::vector<ExternalSet> sets_;  // kExternal
  std::size_t current_ = 0;        // the set of the last frame enqueued
  std::size_t frames_ = 0;         // frames enqueued
  std::vector<SideCopy> list_copies_;
  std::unique_ptr<GlOutputs> gl_;  // kShared, kCopy
  bool device_ordered_ = false;
  std::string why_not_ordered_;
  cl::Event drawable_;
};

// A SwimScene's outputs factory making GlSpeciesOutputs in `renderer` on `hand_off`'s
// path (both must outlive the scene).
tank::OutputsFactory gl_outputs(render::Renderer& renderer, const HandOff& hand_off);

// The renderer's side of one species: its triangles over slots, its outputs' buffers.
struct SpeciesDrawing {
  render::MeshId mesh = 0;
  GlSpeciesOutputs* outputs = nullptr;  // the scene's
  glm::vec3 albedo{0.8f};
  std::vector<std::uint32_t> ids;  // per instance, for the id pass (> 0)
};

// Registers `deformer`'s triangles (over its slots, padding included) for `outputs`.
// `ids`: one per instance.
SpeciesDrawing prepare_drawing(render::Renderer& renderer, const ClDeformer& deformer,
                               GlSpeciesOutputs& outputs, const glm::vec3& albedo,
                               std::vector<std::uint32_t> ids);

// The draw of a species' last frame, straight from its outputs' buffers.
render::FishDraw fish_draw(const SpeciesDrawing& drawing);
// Points `draw` (fish_draw's) at the buffers and list of its outputs' last frame,
// which alternate between two sets on the external path; the rest stays.
void point_at_last_frame(const SpeciesDrawing& drawing, render::FishDraw& draw);

}  // namespace finflex::pictures

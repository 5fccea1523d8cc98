// Where the renderer gets the engine's deformed fish: each species' deformation writes
// GL buffers of the renderer (finflex/gl_outputs.hpp, GlOutputs) and the renderer
// draws them as they are. This is the one point of hand-off between the engine and the
// renderer.
//
// The buffers hold FinFlex's planes (ClDeformer::layout: positions, normals;
// no tangents, which the renderer does not draw) over the deformer's slots, in world
// space (the tank's placements are the deformation's last stage), so they are drawn
// with StreamLayout::planes over remapped_indices() and no transform. Two paths, as
// GlOutputs chooses from the OpenCL context (make_gl_sharing_context):
//  - shared (cl_khr_gl_sharing, NVIDIA): the kernels write the GL buffers between an
//    acquire and a release; nothing goes through the host;
//  - copy (PoCL, or a platform that refused the EGL context): the kernels write a
//    device mirror of each GL buffer, mapped for reading and uploaded with
//    glBufferSubData every frame (the positions and normals once through the host).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/finflex.hpp"
#include "finflex/gl_outputs.hpp"
#include "render/renderer.hpp"
#include "swim_scene.hpp"

namespace finflex::pictures {

// One species' outputs: GL buffers of `renderer` holding `instances` instances of the
// deformer's model in FinFlex's planes (normals in `format`), written through
// GlOutputs. The deformer's context must share the renderer's GL context for the
// shared path (else the copy path runs). Errors: as GlOutputs and
// Renderer::create_buffer.
class GlSpeciesOutputs : public tank::SpeciesOutputs {
 public:
  GlSpeciesOutputs(render::Renderer& renderer, ClDeformer& deformer, std::size_t instances,
                   NormalFormat format);

  DeviceBatch& batch() override { return outputs_.batch(); }
  // GlOutputs::enqueue with the renderer's context current; keeps the event after
  // which GL may draw (wait_until_drawable).
  cl::Event enqueue(ClDeformer& deformer, const ClJob& job,
                    std::vector<cl::Event>* kernel_events) override;
  double handoff_seconds() const override { return outputs_.last_handoff_seconds(); }
  // The copy path waits for the frame's kernels before copying to GL.
  bool waits_for_device() const override { return path() == GlPath::kCopy; }
  void begin_reading() override;
  void end_reading() override;

  GlPath path() const { return outputs_.path(); }
  // Blocks until GL may draw the last frame enqueued (its release, on the shared path).
  void wait_until_drawable();

  const OutputLayout& layout() const { return layout_; }
  render::BufferId positions() const { return positions_; }
  render::BufferId normals() const { return normals_; }
  const render::StreamLayout& position_layout() const { return position_layout_; }
  const render::StreamLayout& normal_layout() const { return normal_layout_; }
  std::size_t instance_count() const { return instances_; }

 private:
  render::Renderer& renderer_;
  OutputLayout layout_;
  render::BufferId positions_ = render::kNoBuffer;
  render::BufferId normals_ = render::kNoBuffer;
  render::StreamLayout position_layout_;
  render::StreamLayout normal_layout_;
  std::size_t instances_ = 0;
  GlOutputs outputs_;
  cl::Event drawable_;
};

// A SwimScene's outputs factory making GlSpeciesOutputs in `renderer` (which must
// outlive the scene).
tank::OutputsFactory gl_outputs(render::Renderer& renderer);

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

// The draw of a species' last frame, straight from its outputs' GL buffers.
render::FishDraw fish_draw(const SpeciesDrawing& drawing);

}  // namespace finflex::pictures

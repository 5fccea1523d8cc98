// Where the renderer gets the engine's deformed fish: one species' DeviceBatch handed
// to render::Renderer as a FishDraw. This is the one point of hand-off between the
// engine and the renderer.
//
// Today the batch goes through the host: each attribute array is mapped for reading
// (the device copies it to the host; a CPU device maps its memory as it is), copied
// into a GL buffer the renderer owns, and unmapped. The engine's output planes
// (finflex/batch.hpp) are drawn as they are, over the deformer's slots
// (remapped_indices()), in world space (the tank's placements are the deformation's
// last stage), so no transform is needed. With OpenCL-GL sharing the engine would
// write into these GL buffers itself and hand_off() would only acquire and release
// them; nothing else would change.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/finflex.hpp"
#include "render/renderer.hpp"

namespace finflex::pictures {

// The renderer's side of one species: its triangles over slots and the GL buffers the
// batch is copied into, sized once for the batch.
struct SpeciesDrawing {
  render::MeshId mesh = 0;
  render::BufferId positions = render::kNoBuffer;
  render::BufferId normals = render::kNoBuffer;
  render::StreamLayout position_layout;
  render::StreamLayout normal_layout;
  std::size_t instance_count = 0;
  glm::vec3 albedo{0.8f};
  std::vector<std::uint32_t> ids;  // per instance, for the id pass (> 0)
};

// Registers `deformer`'s triangles and makes the buffers for `batch` (float32 or half
// normals). `ids`: one per instance of the batch.
SpeciesDrawing prepare_drawing(render::Renderer& renderer, const ClDeformer& deformer,
                               const DeviceBatch& batch, const glm::vec3& albedo,
                               std::vector<std::uint32_t> ids);

// The hand-off: waits for the work queued before it on `queue` (the deformation),
// copies the batch's positions and normals into the drawing's buffers and returns the
// draw. Bytes moved: the batch's positions and normals, once each way through the host.
render::FishDraw hand_off(cl::CommandQueue& queue, const DeviceBatch& batch,
                          render::Renderer& renderer, const SpeciesDrawing& drawing);

}  // namespace finflex::pictures

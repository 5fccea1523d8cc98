// A species at its levels of detail (finflex/detail_levels.hpp), each frame on the
// device: the level choice (finflex/level_choice.hpp) and, per level, the instances it
// chose deformed into that level's outputs. Nothing returns to the host.
//
//   DetailLevels levels = make_detail_levels(swim.model(), {});
//   LevelDeformer fish(context, levels, fish_count);
//   ClDeviceInputs inputs{&driver.parameter_buffer(), &driver.placement_buffer(),
//                         driver.derived_buffer()};
//   each frame: driver.enqueue(...);
//               fish.enqueue(inputs, fish_count, {view});
//               // level k: rows 0 .. counts()[k] of fish.batch(k) hold the instances
//               // fish.chooser().lists() names from list_first(k); draw them with
//               // fish.deformer(k).remapped_indices() and draw_arguments() entry k.
//
// Each level has its own deformer (its mesh is a prefix of level 0's vertices, its rig
// level 0's) and outputs of rows(k) instances (LevelChoiceOptions::level_rows; by
// default the capacity): memory follows the rows, and the work the instances each list
// holds. The full-detail path is ClDeformer over every instance, as before.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/cl_deformer.hpp"
#include "finflex/context.hpp"
#include "finflex/detail_levels.hpp"
#include "finflex/export.hpp"
#include "finflex/level_choice.hpp"

namespace finflex {

class FINFLEX_API LevelDeformer {
 public:
  // Deformers for every level of `levels` (which must outlive this), a chooser for up
  // to `capacity` instances and each level's outputs (FinFlex's planes, normals in
  // `format`; none with own_outputs false: set_batch gives them, or the caller's jobs
  // name their own). Errors: LevelChooser's, ClDeformer's.
  LevelDeformer(Context& context, const DetailLevels& levels, std::size_t capacity,
                const LevelChoiceOptions& options = {},
                NormalFormat format = NormalFormat::kFloat32, bool own_outputs = true);
  ~LevelDeformer();
  LevelDeformer(const LevelDeformer&) = delete;
  LevelDeformer& operator=(const LevelDeformer&) = delete;

  std::size_t level_count() const;
  const DetailLevels& levels() const;
  LevelChooser& chooser();
  ClDeformer& deformer(std::size_t level);
  // Level k's outputs: rows(k) instances. Replace one with a batch of your own (e.g.
  // deformer(k).bind(rows, layout, buffers) over a renderer's memory): kInvalidArgument
  // naming "batch" when it is not deformer(k)'s for chooser().rows(k) instances.
  DeviceBatch& batch(std::size_t level);
  void set_batch(std::size_t level, DeviceBatch batch);

  // Level k's job of a frame: its list's instances of `inputs` (`instances` of them)
  // into batch(k); point job.outputs at other outputs of deformer(k) for rows(k)
  // instances to write those instead.
  ClJob job(std::size_t level, const ClDeviceInputs& inputs, std::size_t instances,
            NormalMode normals = NormalMode::kRotate);

  // After `wait`: the choice for the first `instances` of the inputs seen by `views`,
  // then each level's deformation over its list. inputs.parameters and
  // inputs.placements are needed ("inputs.parameters", "inputs.placements"), each
  // holding `instances` rows; inputs.derived as ClJob's. Returns the last kernel's
  // event; `kernel_events` gets every kernel's (the choice's three first).
  cl::Event enqueue(const ClDeviceInputs& inputs, std::size_t instances,
                    const std::vector<LevelView>& views, NormalMode normals = NormalMode::kRotate,
                    const std::vector<cl::Event>* wait = nullptr,
                    std::vector<cl::Event>* kernel_events = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace finflex

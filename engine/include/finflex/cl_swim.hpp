// The swim driver on an OpenCL device (finflex/swim.hpp has the kinematics): per frame
// the host uploads a few numbers per fish (SwimInput: pose, speed, turning rate) and a
// kernel advances every fish's phases and writes its swim rig's parameters and its
// placement into device buffers that a ClJob then reads, with no copy through the host:
//
//   ClSwimDriver driver(context, swim, lengths);
//   ClDeformer deformer(context, swim.model());
//   ClJob job;
//   job.instances = lengths.size();
//   job.device.parameters = &driver.parameter_buffer();
//   job.device.placements = &driver.placement_buffer();
//   job.device.derived = driver.derived_buffer();  (null: rig_prepare runs)
//   each frame: driver.enqueue(inputs, dt); deformer.enqueue(job);
//
// or, with no copy of the inputs, written straight into the upload's staging memory:
//
//   each frame: SwimInput* in = driver.staged_inputs();  (fill in[0 .. fish_count()))
//               driver.enqueue_staged(dt); deformer.enqueue(job);
//
// The device's state: per fish its wave and pectoral phases (2 floats). Memory per
// fish: 7 floats of inputs (a SwimInput as it is), the rig's values, 16 floats of
// placement. Host work per frame: a copy of the inputs and one pass checking them (the
// check alone for staged inputs).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/context.hpp"
#include "finflex/export.hpp"
#include "finflex/parameters.hpp"
#include "finflex/swim.hpp"

namespace finflex {

class FINFLEX_API ClSwimDriver {
 public:
  // One fish per length (m, > 0), phases from `phases` (cycles) or 0: errors as
  // SwimReference's. The swim model must outlive the driver. items_per_fish: work-items
  // per fish, as ClTuning::table_items (0: the device's choice; a power of two up to 64).
  ClSwimDriver(Context& context, const SwimModel& swim, const std::vector<float>& lengths,
               const std::vector<float>& phases = {}, std::size_t items_per_fish = 0);
  ~ClSwimDriver();
  ClSwimDriver(const ClSwimDriver&) = delete;
  ClSwimDriver& operator=(const ClSwimDriver&) = delete;

  std::size_t fish_count() const;
  // Checks the inputs (check_swim_inputs), uploads them without blocking after `wait`
  // and enqueues the driver kernel. Returns its event.
  cl::Event enqueue(const std::vector<SwimInput>& inputs, float dt,
                    const std::vector<cl::Event>* wait = nullptr);

  // The next frame's inputs, written in place: fish_count() SwimInputs in pinned host
  // memory that the upload reads (on NVIDIA's OpenCL it saves the 280 KB copy of
  // 10,000 fish, docs/swimming.md "Host time"). Waits, if it must, for the upload of
  // the frame that last used this area (three frames ago). The area holds that frame's
  // inputs: write every fish. The same area until enqueue_staged() or enqueue().
  SwimInput* staged_inputs();
  // As enqueue, for the inputs written into staged_inputs(): checks them there
  // (check_swim_inputs; after an error they stay staged, to be mended). From its
  // return on the area belongs to the upload: write the next frame's inputs into the
  // next staged_inputs(). kInvalidArgument "staged_inputs" when none is staged.
  cl::Event enqueue_staged(float dt, const std::vector<cl::Event>* wait = nullptr);

  // What a ClJob reads: rows of the rig's values, and placement records.
  const cl::Buffer& parameter_buffer() const;
  const cl::Buffer& placement_buffer() const;
  // The rig's derived values of the frame (the body spine's records), written by the
  // driver kernel itself when the spine is the rig's only stage with derived values,
  // for ClJob::device.derived: the frame then skips rig_prepare (one launch less).
  // Null otherwise.
  const cl::Buffer* derived_buffer() const;

  // Blocking reads, for tests and tools: the parameters, the wave phases, and the spine
  // segments the last frame bent less than asked (to clear folding), summed.
  RigParameters read_parameters();
  std::vector<float> read_wave_phases();
  std::vector<PlacementRecord> read_placements();
  std::size_t read_limited_segments();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace finflex

// One swim cycle of one fish, for engines that cannot run OpenCL: the fish swims
// straight ahead at a steady speed, its frames sampled evenly over one tail beat, so a
// player that loops them shows no jump.
//
// The cycle's length is the tail-beat period T = 1 / f (f from the swim kinematics for
// the fish's length and speed: finflex/swim.hpp). With N frames the time step is
// dt = T / N, so every step advances the wave's phase by f dt = 1 / N and N steps bring
// it back to where it started: frame k shows phase k / N, and the frame after the last
// is frame 0 again.
//
// Frames are placed in metres in glTF's convention: y up, the head towards +z, the
// body frame's pivot at the origin; the rest pose (the straight fish) is placed alike.
#pragma once

#include <cstddef>
#include <vector>

#include "finflex/finflex.hpp"

namespace finflex::bake {

struct CycleSettings {
  std::size_t frames = 24;  // N, >= 2
  double length_m = 0.4;    // the fish's total length, > 0
  double speed = 1.0;       // through the water, body lengths per second, >= 0
  NormalMode normals = NormalMode::kJacobian;

  // kInvalidArgument naming "frames", "length", "speed" with the value.
  void validate() const;
};

// The cycle's timing and every frame's rig parameters and placement, from the CPU
// driver (SwimReference, double precision).
struct SwimCycle {
  double frequency_hz = 0.0;  // f
  double period_s = 0.0;      // T = 1 / f
  double dt_s = 0.0;          // T / N
  std::size_t frames = 0;     // N
  // N + 1 rows: frames 0 .. N-1, then the rest pose (all values 0).
  RigParameters parameters;
  std::vector<Placement> placements;  // N + 1, all the same
};

// The parameters of the cycle: the driver steps N times by dt from phase 0; step k
// (1..N) is frame k mod N.
SwimCycle plan_cycle(const SwimModel& swim, const CycleSettings& settings);

// The cycle deformed by the engine: instances 0 .. N-1 are the frames, instance N the
// rest pose, host copies in mesh vertex order (ClDeformer::read).
struct BakedCycle {
  SwimCycle cycle;
  DeformedBatch<float> batch;
};
BakedCycle bake_cycle(Context& context, const SwimModel& swim, const CycleSettings& settings);

}  // namespace finflex::bake

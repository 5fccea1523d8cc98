// The swim as `finflex bench --swim` times it: a tank of swimming fish of one species
// (apps/tank), per frame the swim driver kernel, the rig's prepare kernel and the
// deformation with world placement, timed from the driver's start to the deformation's
// end; the host time is the enqueue (inputs gathered and uploaded, launches), the
// tank's simulation excluded. The tank is scaled to keep the density of 1,000 fish in
// the default tank.
//
// Recorded inputs (FrameBenchSettings::recorded_swim_inputs) step the tank for the
// timed frames before they run (a ring of at most kRecordedSwimFrames steps, replayed
// in turn) and each frame copies its step's inputs into the drivers' staging memory,
// so the device is fed as by an application whose simulation keeps ahead of it; live
// inputs step the tank inside the frame loop, and the device waits for the host
// whenever a step takes longer than a frame (10,000 fish: a millisecond or more
// against 0.7 ms of kernels on an H200).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "frame_bench.hpp"
#include "swim_scene.hpp"

namespace finflex::bench {

// Recorded inputs: the tank's steps replayed in turn, at most 64 and at most 256 MiB of
// inputs (64 steps of 10,000 fish: 18 MB).
constexpr std::size_t kRecordedSwimFrames = 64;
constexpr std::size_t kRecordedSwimBytes = std::size_t{256} << 20;

// The swim of `mesh` with the swim rig `rig`, writing the default planes
// (settings.outputs as OutputsChoice{}: kInvalidArgument naming "outputs" otherwise).
// `scene` keeps the tank alive while the result is read.
Measured measure_swim(Context& context, const std::string& mesh, const std::string& rig,
                      const FrameBenchSettings& settings, std::unique_ptr<tank::SwimScene>& scene);

}  // namespace finflex::bench

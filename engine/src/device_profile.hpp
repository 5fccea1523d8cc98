// What the OpenCL backend chooses per device kind, in one place: work-group size,
// instances per work-item and the rig dispatch (the figures behind them are in
// docs/benchmarks.md).
#pragma once

#include <cstddef>

#include "finflex/batch.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/context.hpp"

namespace finflex::detail {

// Work-items per work-group along the slots; every plane stride is a multiple of it.
constexpr std::size_t kWorkGroupSize = ClDeformer::kGroupSize;
static_assert(64 % kWorkGroupSize == 0, "padded_plane_stride must be a multiple of it");

// Instances one work-item deforms. GPUs are limited by the rate of work-items, not of
// bytes, with one instance per work-item: the single bend takes 2 with float32
// normals and 4 with half normals (fewer bytes per instance), the rig kernels 4 (their
// stage frames and parameters are read once for them). CPUs take 1.
inline std::size_t device_instances_per_item(const DeviceDescription& device,
                                             bool single_bend_kernel, NormalFormat format) {
  if (!device.is_gpu()) return 1;
  if (!single_bend_kernel) return 4;
  return format == NormalFormat::kHalf ? 4 : 2;
}

// kPerComponent on GPUs (fewest instructions), kByPathShape on CPUs (straight-line
// kernels, which PoCL's work-group vectoriser needs).
inline RigDispatch device_dispatch(const DeviceDescription& device, RigDispatch asked) {
  if (asked != RigDispatch::kAuto) return asked;
  return device.is_gpu() ? RigDispatch::kPerComponent : RigDispatch::kByPathShape;
}

}  // namespace finflex::detail

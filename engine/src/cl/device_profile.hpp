// What the OpenCL backend chooses per device kind, in one place: work-group size,
// instances and vertex slots per work-item and the rig dispatch (the figures behind
// them are in docs/benchmarks.md).
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>

#include "finflex/batch.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/context.hpp"
#include "finflex/error.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::detail {

// Work-items per work-group along the slots; every plane stride is a multiple of it.
constexpr std::size_t kWorkGroupSize = ClDeformer::kGroupSize;
static_assert(64 % kWorkGroupSize == 0, "padded_plane_stride must be a multiple of it");

// Instances one work-item deforms. GPUs are limited by the rate of work-items, not of
// bytes, with one instance per work-item: the single bend takes 2 with float32
// normals and 4 with half normals (fewer bytes per instance), the rig kernels 4 (a
// vertex's rest values and path serve four instances): 10,000 swimming fish deformed
// in 0.866 ms at 4 against 0.876 at 2 on an H100, 0.697 against 0.748 on an H200.
// `spine_planes`: a rig with a table stage (a spine, whose segment lookup serves them
// too) writing FinFlex's planes with rotated normals takes 8: on an H200, 10,000
// swimming fish 0.667-0.669 ms against 0.678-0.679 at 4 (0.674-0.676 at 16), half
// normals 0.603-0.605 against 0.625. Elsewhere 8 holds more than the registers do:
// Jacobian normals 0.803 against 0.703, octahedral normals 0.361 against 0.297 for
// 4,000, interleaved structs 0.311 against 0.306, and a rig without a table (the Blub
// rig's hinges and bend) 0.247-0.249 against 0.239 for 4,000 (docs/benchmarks.md,
// Swimming, "Eight fish per work-item"). CPUs take 1.
inline std::size_t device_instances_per_item(const DeviceDescription& device,
                                             bool single_bend_kernel, NormalFormat format,
                                             bool spine_planes) {
  if (!device.is_gpu()) return 1;
  if (!single_bend_kernel) return spine_planes ? 8 : 4;
  return format == NormalFormat::kHalf ? 4 : 2;
}

// Whether the kernels take the hardware's sine and cosine (native_sin, native_cos) where
// a vertex needs one of an angle within [-pi, pi] (kernels/deformers/spine.cl, build
// option FF_NATIVE_TRIG): on NVIDIA's GPUs, whose special-function unit runs them beside
// the arithmetic (PTX sin.approx.f32, absolute error about 2^-21 on [-pi, pi]; the
// spine then deviates from the double-precision reference by less than 1e-6 of a body
// length, tests/test_spine.cpp). 10,000 swimming fish deform in 0.697 ms against 0.755
// with the series on an H200 (docs/benchmarks.md). Other devices keep the series: an
// OpenCL native function's accuracy is the implementation's.
inline bool device_native_trig(const DeviceDescription& device) {
  return device.is_gpu() && device.platform_name.find("NVIDIA") != std::string::npos;
}

// Whether the device's OpenCL C compiler is PoCL's (clang): the only one the kernels of
// 32 lanes are built with (kernels/common/lanes.cl: a vector type of clang's).
inline bool device_is_pocl(const DeviceDescription& device) {
  return device.platform_name.find("Portable Computing Language") != std::string::npos;
}

// A CPU's vector of floats as the kernels take it: 16 where the native one has 16 lanes
// (AVX-512), else 8 (AVX2's native vector; two of SSE's).
inline std::size_t device_vector_lanes(const DeviceDescription& device) {
  return device.native_float_vector_width >= 16 ? 16 : 8;
}

// Vertex slots one work-item deforms (kernels/common/lanes.cl). GPUs: 1 (a warp is
// their vector). CPUs: vectors, so the kernels are vector code whatever the OpenCL
// compiler's work-group vectoriser does. On PoCL, two native vectors: two independent
// chains of steps per work-item for one work-item's scalar work. 32 lanes where the
// native vector has 16 (AVX-512; a clang vector type): 1,000 swimming fish on a Xeon
// in a median 0.86 of the time of 16 lanes on 2 threads, 0.93 on 16, 0.97 on a 2-core
// AMD EPYC. 16 where it has 8 (AVX2; PoCL's AVX2 code on those machines): the swim
// in 0.74 of the time of 8 lanes on the Xeon's 2 threads, 0.54 on 16 (8 lanes' stores
// of half a cache line stream slowly there), 0.88 on the AMD EPYC (docs/benchmarks.md,
// "16 lanes on AVX2"). Four native vectors spill: 32 lanes of AVX2 took 1.3 times
// as long as 16, 64 lanes of AVX-512 3 times as long as 32. Elsewhere one vector
// (device_vector_lanes).
inline std::size_t device_lanes(const DeviceDescription& device) {
  if (device.is_gpu()) return 1;
  if (!device_is_pocl(device)) return device_vector_lanes(device);
  const std::size_t native = device.native_float_vector_width;
  return native >= 16 ? 32 : native >= 8 ? 16 : 8;
}

// A CPU's cache that a frame's outputs could stay in, per thread: server CPUs have 1.5
// to 4 MiB of last-level cache and 1 to 2 MiB of L2 per core. The cache size a
// virtual machine reports is often not the host's (480 MiB on 2 cores, measured), so
// the reported size alone is not trusted.
constexpr std::size_t kCacheBytesPerComputeUnit = std::size_t{4} << 20;

// Streaming stores (kernels of more than one lane) for a frame writing `output_bytes`:
// kAuto streams outputs larger than the caches could hold (the reported global memory
// cache, at most kCacheBytesPerComputeUnit per compute unit), which go to memory anyway
// (reading each line before writing it doubles their traffic), and keeps smaller ones
// in the caches. Measured on 2 cores (docs/benchmarks.md, "Streaming stores"): plain
// stores win at 1 MB a frame, both alike at 12 MB, streaming 1.7x faster at 260 MB.
inline bool device_streaming_stores(const DeviceDescription& device, OutputStores asked,
                                    std::size_t output_bytes) {
  if (asked != OutputStores::kAuto) return asked == OutputStores::kStreaming;
  const std::size_t units = device.compute_units > 0 ? device.compute_units : 1;
  const std::size_t cache_bytes =
      std::min(device.global_memory_cache_bytes, units * kCacheBytesPerComputeUnit);
  return output_bytes > cache_bytes;
}

// Work-items that share one instance's table work (rig_prepare, the swim driver) of
// `samples` samples: on GPUs one per sample, the smallest power of two that holds them
// and at most a work-group (the samples in parallel, summed by a scan in local memory;
// the swim driver of 10,000 fish of 32 samples took 0.024 ms on an H100 with 32
// work-items per fish, 0.033-0.048 with 64, 0.06 with 4 or 8, 0.10 with 1:
// docs/results/2026-11-24_swim_driver_items.txt); 1 on CPUs (a work-group's 64
// instances each one work-item's loop: PoCL runs the work-items of a group between
// barriers as loops).
inline std::size_t device_table_items(const DeviceDescription& device, std::size_t samples,
                                      std::size_t asked = 0) {
  if (asked != 0) return asked;
  if (!device.is_gpu()) return 1;
  std::size_t items = 1;
  while (items < samples && items < kWorkGroupSize) items *= 2;
  return items;
}

// Fish one work-item of the swim driver takes, one per lane (kernels/swim/driver.cl):
// on CPUs, with one work-item per fish, a vector's worth (device_vector_lanes), so the driver
// is vector code (on 2 cores with PoCL, 1,000 fish: 0.45-0.65 ms a frame one fish per
// work-item, the trigonometry scalar); else 1.
inline std::size_t device_driver_lanes(const DeviceDescription& device, std::size_t items) {
  return items == 1 && !device.is_gpu() ? device_vector_lanes(device) : 1;
}

// The swim driver's work-group with that many fish per work-item: a few work-items
// (64 fish) when they are lanes, so 1,000 fish still make 16 groups for the threads
// to share; else table_group_size.
constexpr std::size_t kLaneDriverGroupSize = 4;

// Checks a table_items option (ClTuning, ClSwimDriver): 0, or a power of two up to
// kWorkGroupSize.
inline void check_table_items(std::size_t items, const char* field) {
  if (items <= kWorkGroupSize && (items & (items - 1)) == 0) return;
  throw Error(ErrorCode::kInvalidArgument, field,
              std::string(field) + ": " + std::to_string(items) +
                  " work-items per instance (expected 0: the device's choice, or a power of "
                  "two up to " +
                  std::to_string(kWorkGroupSize) + ")");
}

// The work-group of the kernels that share out a table (rig_prepare, swim_drive):
// kWorkGroupSize instances side by side with one work-item each, else one instance's
// `items` work-items, so that a group never holds both an instance and one past the
// last (which returns before the barriers the others wait at).
inline std::size_t table_group_size(std::size_t items) {
  return items == 1 ? kWorkGroupSize : items;
}

// kPerComponent on GPUs (fewest instructions), kByPathShape on CPUs (straight-line
// one-lane kernels, which PoCL's work-group vectoriser needs; their kernels of more
// than one lane are one kernel with each component's stages compiled in,
// rig_dispatch_source).
inline RigDispatch device_dispatch(const DeviceDescription& device, RigDispatch asked) {
  if (asked != RigDispatch::kAuto) return asked;
  return device.is_gpu() ? RigDispatch::kPerComponent : RigDispatch::kByPathShape;
}

}  // namespace finflex::detail

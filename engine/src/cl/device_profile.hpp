// What the OpenCL backend chooses per device: a table of data, a row per class of
// device (kDeviceChoices), each column's reason a line with a link to its measurement
// in docs/benchmarks.md#measured-choices; the device_* functions look a device's row
// up. The choices that follow a formula (streaming stores, table items) are small
// functions beside the table.
#pragma once

#include <algorithm>
#include <array>
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

// PoCL's platform name. Its OpenCL C compiler (clang) is the only one the kernels of 32
// lanes are built with (kernels/common/lanes.cl: a vector type of clang's).
constexpr const char* kPoclPlatform = "Portable Computing Language";

// How many work-items share one instance's table work (rig_prepare, the swim driver).
enum class TableItems {
  kOne,        // one work-item per instance (a work-group's instances each one loop)
  kPerSample,  // one per sample (table_items_for: a power of two up to a work-group)
};

// A class of devices and what the backend chooses for it, a column a choice with its
// reason; a device is in the first row it matches (device_choices).
struct DeviceChoices {
  const char* name;
  bool gpu;                   // a GPU, or not (CPUs and any other device)
  const char* platform;       // a part of the platform's name, "" for any
  std::size_t native_floats;  // the least CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT ("width")
  // "instances" per work-item: the single bend with float32 normals and with half normals, a
  // rig, a rig with a table stage (a spine) writing FinFlex's planes with rotated normals.
  // GPUs go at the rate of work-items (docs/benchmarks.md#choice-gpu-instances-per-item).
  std::size_t bend_instances, bend_half_instances, rig_instances, spine_planes_instances;
  // Slots per work-item: a vector on CPUs (docs/benchmarks.md#choice-cpu-lanes), two on PoCL
  // (#choice-two-vectors, #choice-avx2-lanes); a GPU's warp is its vector.
  std::size_t lanes;
  // kAuto's: fewest instructions, or straight-line for PoCL (docs/benchmarks.md#choice-dispatch).
  RigDispatch dispatch;
  // The hardware's sin and cos where their error is known (docs/benchmarks.md#choice-native-trig).
  bool native_trig;
  // Work-items an instance's table work takes (docs/benchmarks.md#choice-table-items).
  TableItems table_items;
  // "swim": fish per work-item of the swim driver, one work-item a fish: a vector's worth on
  // CPUs (docs/benchmarks.md#choice-driver-lanes).
  std::size_t driver_lanes;
};

// The rows, in the order they are matched: the last GPU row and the last row match
// every GPU and every other device.
inline constexpr std::array<DeviceChoices, 7> kDeviceChoices = [] {
  constexpr const char* kAny = "";
  constexpr const char* kPocl = kPoclPlatform;
  constexpr RigDispatch kPerComponent = RigDispatch::kPerComponent;
  constexpr RigDispatch kByPathShape = RigDispatch::kByPathShape;
  constexpr TableItems kOne = TableItems::kOne;
  constexpr TableItems kPerSample = TableItems::kPerSample;
  // clang-format off
  return std::array<DeviceChoices, 7>{{
    // name          gpu    platform  width instances   lanes dispatch       trig   items       swim
    {"NVIDIA GPU",   true,  "NVIDIA", 0,    2, 4, 4, 8, 1,    kPerComponent, true,  kPerSample, 1},
    {"other GPU",    true,  kAny,     0,    2, 4, 4, 8, 1,    kPerComponent, false, kPerSample, 1},
    {"PoCL AVX-512", false, kPocl,    16,   1, 1, 1, 1, 32,   kByPathShape,  false, kOne,       16},
    {"PoCL AVX2",    false, kPocl,    8,    1, 1, 1, 1, 16,   kByPathShape,  false, kOne,       8},
    {"PoCL",         false, kPocl,    0,    1, 1, 1, 1, 8,    kByPathShape,  false, kOne,       8},
    {"CPU AVX-512",  false, kAny,     16,   1, 1, 1, 1, 16,   kByPathShape,  false, kOne,       16},
    {"other CPU",    false, kAny,     0,    1, 1, 1, 1, 8,    kByPathShape,  false, kOne,       8},
  }};
  // clang-format on
}();

// Whether the device's OpenCL C compiler is PoCL's.
inline bool device_is_pocl(const DeviceDescription& device) {
  return device.platform_name.find(kPoclPlatform) != std::string::npos;
}

// The device's row of kDeviceChoices.
inline const DeviceChoices& device_choices(const DeviceDescription& device) {
  for (const DeviceChoices& row : kDeviceChoices) {
    if (row.gpu == device.is_gpu() && device.native_float_vector_width >= row.native_floats &&
        device.platform_name.find(row.platform) != std::string::npos) {
      return row;
    }
  }
  return kDeviceChoices.back();
}

// Instances one work-item deforms. `spine_planes`: a rig with a table stage (a spine)
// writing FinFlex's planes with rotated normals.
inline std::size_t device_instances_per_item(const DeviceDescription& device,
                                             bool single_bend_kernel, NormalFormat format,
                                             bool spine_planes) {
  const DeviceChoices& row = device_choices(device);
  if (!single_bend_kernel) return spine_planes ? row.spine_planes_instances : row.rig_instances;
  return format == NormalFormat::kHalf ? row.bend_half_instances : row.bend_instances;
}

// Whether the kernels take the hardware's sine and cosine (native_sin, native_cos) where
// a vertex needs one of an angle within [-pi, pi] (kernels/deformers/spine.cl, build
// option FF_NATIVE_TRIG); the spine then stays within tests/test_spine.cpp's bounds.
inline bool device_native_trig(const DeviceDescription& device) {
  return device_choices(device).native_trig;
}

// Vertex slots one work-item deforms (kernels/common/lanes.cl).
inline std::size_t device_lanes(const DeviceDescription& device) {
  return device_choices(device).lanes;
}

// RigDispatch::kAuto as the device's choice; any other as asked.
inline RigDispatch device_dispatch(const DeviceDescription& device, RigDispatch asked) {
  if (asked != RigDispatch::kAuto) return asked;
  return device_choices(device).dispatch;
}

// The most cache per compute unit a frame's outputs are taken to stay in: server CPUs
// have 1.5 to 4 MiB of last-level cache a core, and a virtual machine may report the
// host's (docs/benchmarks.md#choice-streaming-stores).
constexpr std::size_t kCacheBytesPerComputeUnit = std::size_t{4} << 20;

// Streaming stores (kernels of more than one lane) for a frame writing `output_bytes`:
// kAuto streams outputs larger than the caches could hold (the reported global memory
// cache, at most kCacheBytesPerComputeUnit per compute unit), which go to memory anyway,
// and keeps smaller ones in the caches (docs/benchmarks.md#choice-streaming-stores).
inline bool device_streaming_stores(const DeviceDescription& device, OutputStores asked,
                                    std::size_t output_bytes) {
  if (asked != OutputStores::kAuto) return asked == OutputStores::kStreaming;
  const std::size_t units = device.compute_units > 0 ? device.compute_units : 1;
  const std::size_t cache_bytes =
      std::min(device.global_memory_cache_bytes, units * kCacheBytesPerComputeUnit);
  return output_bytes > cache_bytes;
}

// TableItems::kPerSample for `samples` samples: the smallest power of two that holds
// them, at most a work-group (summed by a scan in local memory,
// docs/benchmarks.md#choice-table-items).
inline std::size_t table_items_for(std::size_t samples) {
  std::size_t items = 1;
  while (items < samples && items < kWorkGroupSize) items *= 2;
  return items;
}

// Work-items that share one instance's table work (rig_prepare, the swim driver) of
// `samples` samples: `asked` unless 0, else the device's choice.
inline std::size_t device_table_items(const DeviceDescription& device, std::size_t samples,
                                      std::size_t asked = 0) {
  if (asked != 0) return asked;
  if (device_choices(device).table_items == TableItems::kOne) return 1;
  return table_items_for(samples);
}

// Fish one work-item of the swim driver takes, one per lane (kernels/swim/driver.cl),
// with `items` work-items per fish: the device's driver lanes for one, else 1.
inline std::size_t device_driver_lanes(const DeviceDescription& device, std::size_t items) {
  return items == 1 ? device_choices(device).driver_lanes : 1;
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

}  // namespace finflex::detail

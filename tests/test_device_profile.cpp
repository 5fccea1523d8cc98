// The per-device choices (engine/src/cl/device_profile.hpp) for described devices: an
// NVIDIA GPU, an AMD GPU, PoCL on CPUs with AVX-512, AVX2 and narrower vectors, and
// CPUs of another OpenCL implementation. The expected values are written out here, each
// as the backend has chosen it, so that the table and its lookups are checked against
// them and not against themselves. No device is needed.
#include <cstddef>
#include <string>

#include <gtest/gtest.h>

#include "cl/device_profile.hpp"

namespace finflex::detail {
namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;

DeviceDescription device(const std::string& platform, const std::string& type,
                         std::size_t native_floats, std::size_t cache_bytes = 0,
                         std::size_t compute_units = 1) {
  DeviceDescription d;
  d.platform_name = platform;
  d.device_name = platform + " " + type;
  d.type = type;
  d.native_float_vector_width = native_floats;
  d.global_memory_cache_bytes = cache_bytes;
  d.compute_units = compute_units;
  return d;
}

DeviceDescription nvidia_gpu() { return device("NVIDIA CUDA", "GPU", 1, 50 * kMiB, 132); }
DeviceDescription amd_gpu() {
  return device("AMD Accelerated Parallel Processing", "GPU", 4, 16 * kMiB, 104);
}
DeviceDescription pocl_avx512() {
  return device("Portable Computing Language", "CPU", 16, 36 * kMiB, 16);
}
DeviceDescription pocl_avx2() {
  return device("Portable Computing Language", "CPU", 8, 480 * kMiB, 2);
}
DeviceDescription pocl_sse() {
  return device("Portable Computing Language", "CPU", 4, 8 * kMiB, 4);
}
DeviceDescription intel_cpu_avx2() { return device("Intel(R) OpenCL", "CPU", 8, 32 * kMiB, 8); }
DeviceDescription intel_cpu_avx512() { return device("Intel(R) OpenCL", "CPU", 16, 32 * kMiB, 8); }
DeviceDescription accelerator() { return device("Some Vendor", "accelerator", 8, 0, 1); }

// What a device's choices were, written out.
struct Expected {
  std::size_t bend, bend_half, rig, spine_planes;  // device_instances_per_item
  bool native_trig;
  bool pocl;
  std::size_t lanes;
  RigDispatch dispatch;
  bool table_items_per_sample;  // device_table_items: one per sample, else 1
  std::size_t driver_lanes;     // device_driver_lanes with one work-item per fish
};

void expect_choices(const DeviceDescription& d, const Expected& e) {
  SCOPED_TRACE(d.device_name + ", " + std::to_string(d.native_float_vector_width) + " floats");
  EXPECT_EQ(device_instances_per_item(d, true, NormalFormat::kFloat32, false), e.bend);
  EXPECT_EQ(device_instances_per_item(d, true, NormalFormat::kFloat32, true), e.bend);
  EXPECT_EQ(device_instances_per_item(d, true, NormalFormat::kHalf, false), e.bend_half);
  EXPECT_EQ(device_instances_per_item(d, true, NormalFormat::kHalf, true), e.bend_half);
  EXPECT_EQ(device_instances_per_item(d, false, NormalFormat::kFloat32, false), e.rig);
  EXPECT_EQ(device_instances_per_item(d, false, NormalFormat::kHalf, false), e.rig);
  EXPECT_EQ(device_instances_per_item(d, false, NormalFormat::kFloat32, true), e.spine_planes);
  EXPECT_EQ(device_instances_per_item(d, false, NormalFormat::kHalf, true), e.spine_planes);
  EXPECT_EQ(device_native_trig(d), e.native_trig);
  EXPECT_EQ(device_is_pocl(d), e.pocl);
  EXPECT_EQ(device_lanes(d), e.lanes);
  EXPECT_EQ(device_dispatch(d, RigDispatch::kAuto), e.dispatch);
  for (RigDispatch asked : {RigDispatch::kPerComponent, RigDispatch::kByPathShape})
    EXPECT_EQ(device_dispatch(d, asked), asked);
  // Samples -> work-items when they share one instance's table work: the smallest power
  // of two that holds them, at most a work-group.
  const std::size_t samples[][2] = {{0, 1},   {1, 1},   {2, 2},   {5, 8},    {32, 32},
                                    {33, 64}, {64, 64}, {65, 64}, {1000, 64}};
  for (const auto& [count, per_sample] : samples) {
    EXPECT_EQ(device_table_items(d, count), e.table_items_per_sample ? per_sample : 1u) << count;
    EXPECT_EQ(device_table_items(d, count, 4), 4u) << count;
  }
  EXPECT_EQ(device_driver_lanes(d, 1), e.driver_lanes);
  for (std::size_t items : {2, 8, 32, 64}) EXPECT_EQ(device_driver_lanes(d, items), 1u);
}

TEST(DeviceProfile, NvidiaGpu) {
  expect_choices(nvidia_gpu(), {2, 4, 4, 8, true, false, 1, RigDispatch::kPerComponent, true, 1});
}

TEST(DeviceProfile, OtherGpu) {
  expect_choices(amd_gpu(), {2, 4, 4, 8, false, false, 1, RigDispatch::kPerComponent, true, 1});
}

TEST(DeviceProfile, PoclCpuWithAvx512) {
  expect_choices(pocl_avx512(),
                 {1, 1, 1, 1, false, true, 32, RigDispatch::kByPathShape, false, 16});
}

TEST(DeviceProfile, PoclCpuWithAvx2) {
  expect_choices(pocl_avx2(), {1, 1, 1, 1, false, true, 16, RigDispatch::kByPathShape, false, 8});
}

TEST(DeviceProfile, PoclCpuWithNarrowerVectors) {
  expect_choices(pocl_sse(), {1, 1, 1, 1, false, true, 8, RigDispatch::kByPathShape, false, 8});
}

TEST(DeviceProfile, OtherCpus) {
  expect_choices(intel_cpu_avx2(),
                 {1, 1, 1, 1, false, false, 8, RigDispatch::kByPathShape, false, 8});
  expect_choices(intel_cpu_avx512(),
                 {1, 1, 1, 1, false, false, 16, RigDispatch::kByPathShape, false, 16});
  expect_choices(accelerator(), {1, 1, 1, 1, false, false, 8, RigDispatch::kByPathShape, false, 8});
}

TEST(DeviceProfile, EveryDeviceHasARow) {
  for (const DeviceDescription& d : {nvidia_gpu(), amd_gpu(), pocl_avx512(), pocl_avx2(),
                                     pocl_sse(), intel_cpu_avx2(), intel_cpu_avx512()}) {
    EXPECT_EQ(device_choices(d).gpu, d.is_gpu()) << d.device_name;
  }
  EXPECT_STREQ(device_choices(nvidia_gpu()).name, "NVIDIA GPU");
  EXPECT_STREQ(device_choices(amd_gpu()).name, "other GPU");
  EXPECT_STREQ(device_choices(pocl_avx512()).name, "PoCL AVX-512");
  EXPECT_STREQ(device_choices(pocl_avx2()).name, "PoCL AVX2");
  EXPECT_STREQ(device_choices(intel_cpu_avx2()).name, "other CPU");
}

// Streaming stores: the reported cache, at most 4 MiB per compute unit, is the line.
TEST(DeviceProfile, StreamingStoresAboveTheCaches) {
  const DeviceDescription xeon = pocl_avx512();  // 36 MiB, 16 units: 36 MiB
  EXPECT_FALSE(device_streaming_stores(xeon, OutputStores::kAuto, 36 * kMiB));
  EXPECT_TRUE(device_streaming_stores(xeon, OutputStores::kAuto, 36 * kMiB + 1));
  const DeviceDescription vm = pocl_avx2();  // reports 480 MiB on 2 units: 8 MiB
  EXPECT_FALSE(device_streaming_stores(vm, OutputStores::kAuto, 8 * kMiB));
  EXPECT_TRUE(device_streaming_stores(vm, OutputStores::kAuto, 8 * kMiB + 1));
  DeviceDescription no_units = pocl_avx2();  // 0 units count as 1: 4 MiB
  no_units.compute_units = 0;
  EXPECT_FALSE(device_streaming_stores(no_units, OutputStores::kAuto, 4 * kMiB));
  EXPECT_TRUE(device_streaming_stores(no_units, OutputStores::kAuto, 4 * kMiB + 1));
  for (const DeviceDescription& d : {xeon, vm, nvidia_gpu()}) {
    EXPECT_TRUE(device_streaming_stores(d, OutputStores::kStreaming, 1));
    EXPECT_FALSE(device_streaming_stores(d, OutputStores::kPlain, std::size_t{1} << 40));
  }
}

TEST(DeviceProfile, TableGroupsAndItemChecks) {
  EXPECT_EQ(table_group_size(1), 64u);
  EXPECT_EQ(table_group_size(2), 2u);
  EXPECT_EQ(table_group_size(32), 32u);
  EXPECT_EQ(table_group_size(64), 64u);
  for (std::size_t items : {0, 1, 2, 4, 8, 16, 32, 64}) {
    EXPECT_NO_THROW(check_table_items(items, "tuning.table_items")) << items;
  }
  for (std::size_t items : {3, 6, 48, 128}) {
    EXPECT_THROW(check_table_items(items, "tuning.table_items"), Error) << items;
  }
}

}  // namespace
}  // namespace finflex::detail

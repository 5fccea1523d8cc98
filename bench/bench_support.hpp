// Shared pieces of the FinFlex Google Benchmark programs: the device, the mesh and its
// models, and the counters every benchmark reports. The harness they share with
// `finflex bench` (timing from profiling events, the reference kernels, jobs and
// parameters, what a deformer reports) is in support/.
#pragma once

#include <chrono>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "deformer_report.hpp"
#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "frame_bench.hpp"
#include "reference_kernels.hpp"
#include "timing.hpp"

namespace finflex::bench {

std::string env_or(const char* name, const std::string& fallback);

// A model on the device with its batches by (instances, normal format).
struct DeviceModel {
  RiggedMesh model;
  ClDeformer deformer;
  std::map<std::pair<std::size_t, NormalFormat>, DeviceBatch> batches;

  DeviceModel(Context& context, RiggedMesh rigged)
      : model(std::move(rigged)), deformer(context, model) {}
  DeviceBatch& batch(std::size_t instances, NormalFormat format = NormalFormat::kFloat32);
  // A job over `batch` with `values`.
  ClJob job(const RigParameters& values, DeviceBatch& batch, NormalMode normals,
            RigPath path = RigPath::kAuto) const;
};

// One context, mesh and set of models for the whole program: FINFLEX_DEVICE (default
// device), FINFLEX_MESH (data/blub/fish.obj), FINFLEX_RIG (data/rigs/blub.rig.json).
struct Setup {
  Context context{env_or("FINFLEX_DEVICE", "")};
  std::string mesh_path = env_or("FINFLEX_MESH", std::string(FINFLEX_DATA_DIR) + "/blub/fish.obj");
  Mesh mesh = load_mesh(mesh_path);
  BodyFrame frame = find_body_frame(mesh);
  // Bytes/s of the write-only kernel by (instances, normal format), measured earlier
  // in this run.
  std::map<std::pair<std::size_t, NormalFormat>, double> write_only_bytes_per_second;
  // Source of the copy kernel: rest-sized planes.
  cl::Buffer copy_source{context.context(), CL_MEM_READ_ONLY,
                         padded_plane_stride(mesh.vertex_count()) * 6 * sizeof(float)};

  static Setup& get();
  // The whole-body bend in `mode`, and the shipped rig, made on first use.
  DeviceModel& bend(BendMode mode);
  DeviceModel& rig();

 private:
  std::map<BendMode, std::unique_ptr<DeviceModel>> bends_;
  std::unique_ptr<DeviceModel> rig_;
};

// Bytes one launch writes: positions and normals (in the layout's format) over the
// padded planes.
double written_bytes(const BatchShape& layout);

// vertices/s, bytes/s (written), instances, vertices; and write_fraction when the
// write-only kernel was measured for this instance count.
void set_counters(benchmark::State& state, const BatchShape& layout, double seconds);

// The baselines' values of m for `instances` instances: fractions of the limit for
// x_max, both signs (the same for every baseline).
std::vector<float> baseline_bend_values(std::size_t instances, double x_max);
// The counters of set_counters for a baseline's `instances` instances of the mesh
// (outputs over unpadded arrays) deformed in `seconds`.
void set_baseline_counters(benchmark::State& state, std::size_t instances, double seconds);

// The host seconds `work` takes (a baseline's frame on the CPU, for time_iterations).
template <typename Work>
double host_seconds(Work&& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs `launch` (returning the device seconds of one frame) once to warm up (PoCL
// compiles per work-group shape), then times it; returns the total seconds.
template <typename Launch>
double time_iterations(benchmark::State& state, Launch launch) {
  launch();
  double total = 0.0;
  for (auto _ : state) {
    const double seconds = launch();
    state.SetIterationTime(seconds);
    total += seconds;
  }
  return total;
}

// Benchmark bodies (bench_bend.cpp, bench_rig.cpp, bench_baselines.cpp); registered in
// bench_main.cpp.
// per_item, lanes: 0 for the bend deformer's own (kernel_shape, deformer_report.hpp);
// streaming: with more than one lane, streaming stores (ClTuning::stores).
void BM_WriteOnly(benchmark::State& state, NormalFormat format, std::size_t per_item,
                  WriteValues values, std::size_t lanes, bool streaming);
void BM_CopyRest(benchmark::State& state);
void BM_Bend(benchmark::State& state, BendMode mode, NormalMode normals, NormalFormat format);
void BM_Rig(benchmark::State& state, RigPath path);
void BM_OpenMPBaseline(benchmark::State& state);
void BM_OpenMPSimdBaseline(benchmark::State& state);
void BM_HostOverhead(benchmark::State& state);
void BM_DoubleReference(benchmark::State& state);

}  // namespace finflex::bench

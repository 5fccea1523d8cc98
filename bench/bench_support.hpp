// Shared pieces of the FinFlex benchmarks: the device, the mesh, kernel timing from
// OpenCL profiling events, and the counters every benchmark reports.
#pragma once

#include <cstdlib>
#include <map>
#include <string>
#include <utility>

#include <benchmark/benchmark.h>

#include "finflex/finflex.hpp"

namespace finflex::bench {

std::string env_or(const char* name, const std::string& fallback);

// One context, mesh and bend deformer for the whole program: FINFLEX_DEVICE (default
// device), FINFLEX_MESH (data/blub/fish.obj).
struct Setup {
  Context context{env_or("FINFLEX_DEVICE", "")};
  std::string mesh_path = env_or("FINFLEX_MESH", std::string(FINFLEX_DATA_DIR) + "/blub/fish.obj");
  Mesh mesh = load_mesh(mesh_path);
  LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer{context, local};
  std::map<std::pair<std::size_t, NormalFormat>, DeviceBatch> batches;
  // Bytes/s of the write-only kernel by (instances, normal format), measured earlier
  // in this run.
  std::map<std::pair<std::size_t, NormalFormat>, double> write_only_bytes_per_second;
  std::map<std::string, cl::Kernel> kernels;
  // Source of the copy kernel: rest-sized planes (the deformer's own are private).
  cl::Buffer copy_source{context.context(), CL_MEM_READ_ONLY,
                         padded_plane_stride(local.vertex_count()) * 6 * sizeof(float)};

  static Setup& get();
  DeviceBatch& batch(std::size_t instances, NormalFormat format = NormalFormat::kFloat32);
  cl::Kernel& kernel(const std::string& name);  // of the bend program, default options
};

// Waits for `event` and returns its device time (end - start).
double event_seconds(const cl::Event& event);
// From the start of `first` to the end of `last` (a sequence of kernels).
double span_seconds(const cl::Event& first, const cl::Event& last);

// Bytes one launch writes: positions and normals (in the layout's format) over the
// padded planes.
double written_bytes(const BatchLayout& layout);

// vertices/s, bytes/s (written), instances, vertices; and write_fraction when the
// write-only kernel was measured for this instance count.
void set_counters(benchmark::State& state, const BatchLayout& layout, double seconds);

// Runs `launch` (returning the device seconds of one frame) once to warm up (PoCL
// compiles per work-group shape), then times it; returns the total seconds.
template <typename Launch>
double time_frames(benchmark::State& state, Launch launch) {
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
void BM_WriteOnly(benchmark::State& state, NormalFormat format, std::size_t per_item,
                  WriteValues values);
void BM_CopyRest(benchmark::State& state);
void BM_Bend(benchmark::State& state, BendSettings settings, NormalFormat format);
void BM_Rig(benchmark::State& state, RigPath path);
void BM_OpenMPBaseline(benchmark::State& state);
void BM_HostOverhead(benchmark::State& state);
void BM_DoubleReference(benchmark::State& state);

}  // namespace finflex::bench

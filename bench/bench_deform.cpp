// Throughput of the batched bend on the default OpenCL device (or FINFLEX_DEVICE),
// next to a write-only kernel and a copy kernel of the same NDRange and output planes,
// measured in the same run. Times are the kernels' own, from OpenCL profiling events,
// after a warm-up launch of every kernel shape.
//
//   build/bench/bench_deform --benchmark_counters_tabular=true
//   FINFLEX_MESH=path/to/mesh.obj FINFLEX_DEVICE=H100 build/bench/bench_deform
//
// Counters: vertices/s (deformed vertices, all instances), bytes/s (bytes written:
// 24 per vertex, positions + normals in float32), and for the bend the fraction of
// the write-only kernel's bandwidth (write_fraction), both from this run.
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "finflex/finflex.hpp"

namespace finflex {
namespace {

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : fallback;
}

// One context, mesh and deformer for the whole program.
struct Setup {
  Context context{env_or("FINFLEX_DEVICE", "")};
  Mesh mesh = load_mesh(env_or("FINFLEX_MESH", std::string(FINFLEX_DATA_DIR) + "/blub/fish.obj"));
  LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer{context, local};
  std::map<std::size_t, DeviceBatch> batches;
  std::map<std::size_t, double> write_only_bytes_per_second;
  std::map<std::string, cl::Kernel> kernels;
  // Source of the copy kernel: rest-sized planes (the deformer's own are private).
  cl::Buffer copy_source{context.context(), CL_MEM_READ_ONLY,
                         padded_plane_stride(local.vertex_count()) * 6 * sizeof(float)};

  static Setup& get() {
    static Setup setup;
    return setup;
  }
  DeviceBatch& batch(std::size_t instances) {
    auto found = batches.find(instances);
    if (found == batches.end())
      found = batches.emplace(instances, deformer.allocate(instances)).first;
    return found->second;
  }
  cl::Kernel& kernel(const std::string& name) {
    auto found = kernels.find(name);
    if (found == kernels.end()) found = kernels.emplace(name, context.kernel(name, ProgramSource::bend_batch(), "")).first;
    return found->second;
  }
};

double event_seconds(const cl::Event& event) {
  check_cl(event.wait(), "clWaitForEvents");
  const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-9;
}

// Bytes one launch writes: positions and normals in float32 over the padded planes.
double written_bytes(const BatchLayout& layout) {
  return static_cast<double>(layout.plane_stride * layout.instance_count) * 24.0;
}

void set_counters(benchmark::State& state, const BatchLayout& layout) {
  const double vertices = static_cast<double>(layout.vertex_count * layout.instance_count);
  const double bytes = written_bytes(layout);
  const auto rate = benchmark::Counter::kIsIterationInvariantRate;
  state.counters["vertices/s"] = benchmark::Counter(vertices, rate);
  state.counters["bytes/s"] = benchmark::Counter(bytes, rate);  // SI: 1 G = 1e9
  state.counters["instances"] = static_cast<double>(layout.instance_count);
  state.counters["vertices"] = static_cast<double>(layout.vertex_count);
}

// Runs `launch` once to warm up (PoCL compiles per work-group shape), then times it.
template <typename Launch>
double time_kernel(benchmark::State& state, Launch launch) {
  event_seconds(launch());
  double total = 0.0;
  for (auto _ : state) {
    const double seconds = event_seconds(launch());
    state.SetIterationTime(seconds);
    total += seconds;
  }
  return total;
}

// Times `kernel` (arguments set) over the batch's NDRange, as bend_batch runs.
double time_batch_kernel(benchmark::State& state, cl::Kernel& kernel, const BatchLayout& layout) {
  Setup& setup = Setup::get();
  return time_kernel(state, [&] {
    cl::Event done;
    check_cl(setup.context.queue().enqueueNDRangeKernel(
                 kernel, cl::NullRange, cl::NDRange(layout.plane_stride, layout.instance_count),
                 cl::NDRange(ClDeformer::kLocalSize, 1), nullptr, &done),
             "clEnqueueNDRangeKernel");
    return done;
  });
}

void BM_WriteOnly(benchmark::State& state) {
  Setup& setup = Setup::get();
  DeviceBatch& batch = setup.batch(static_cast<std::size_t>(state.range(0)));
  cl::Kernel& kernel = setup.kernel("write_planes");
  kernel.setArg(0, batch.positions);
  kernel.setArg(1, batch.normals);
  kernel.setArg(2, static_cast<cl_uint>(batch.layout.plane_stride));
  kernel.setArg(3, 1.0f);
  const double seconds = time_batch_kernel(state, kernel, batch.layout);
  set_counters(state, batch.layout);
  setup.write_only_bytes_per_second[batch.layout.instance_count] =
      written_bytes(batch.layout) * static_cast<double>(state.iterations()) / seconds;
}

void BM_CopyRest(benchmark::State& state) {
  Setup& setup = Setup::get();
  DeviceBatch& batch = setup.batch(static_cast<std::size_t>(state.range(0)));
  cl::Kernel& kernel = setup.kernel("copy_rest");
  kernel.setArg(0, setup.copy_source);
  kernel.setArg(1, batch.positions);
  kernel.setArg(2, batch.normals);
  kernel.setArg(3, static_cast<cl_uint>(batch.layout.plane_stride));
  time_batch_kernel(state, kernel, batch.layout);
  set_counters(state, batch.layout);
}

void BM_Bend(benchmark::State& state, BendSettings settings) {
  Setup& setup = Setup::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = setup.batch(instances);
  std::vector<float> m(instances);
  const float limit = static_cast<float>(max_abs_m(setup.local.x_max));
  for (std::size_t i = 0; i < instances; ++i)
    m[i] = limit * (static_cast<float>(i % 17) / 8.0f - 1.0f);
  const double seconds =
      time_kernel(state, [&] { return setup.deformer.enqueue(m, settings, batch); });
  set_counters(state, batch.layout);
  const auto write_only = setup.write_only_bytes_per_second.find(instances);
  if (write_only != setup.write_only_bytes_per_second.end()) {
    state.counters["write_fraction"] = written_bytes(batch.layout) *
                                       static_cast<double>(state.iterations()) / seconds /
                                       write_only->second;
  }
}

void instance_counts(benchmark::internal::Benchmark* b) {
  for (int n : {1, 10, 100, 1000, 4000}) b->Arg(n);
  b->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
}

BENCHMARK(BM_WriteOnly)->Apply(instance_counts);
BENCHMARK(BM_CopyRest)->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, paper_rotate, BendSettings{BendMode::kPaper, NormalMode::kRotate})
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, exact_rotate, BendSettings{BendMode::kExact, NormalMode::kRotate})
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, paper_jacobian, BendSettings{BendMode::kPaper, NormalMode::kJacobian})
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, exact_jacobian, BendSettings{BendMode::kExact, NormalMode::kJacobian})
    ->Apply(instance_counts);

}  // namespace
}  // namespace finflex

BENCHMARK_MAIN();

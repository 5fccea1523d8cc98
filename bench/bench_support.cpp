#include "bench_support.hpp"

namespace finflex::bench {

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : fallback;
}

Setup& Setup::get() {
  static Setup setup;
  return setup;
}

DeviceBatch& Setup::batch(std::size_t instances, NormalFormat format) {
  const auto key = std::make_pair(instances, format);
  auto found = batches.find(key);
  if (found == batches.end()) {
    found = batches.emplace(key, deformer.allocate(instances, format)).first;
  }
  return found->second;
}

cl::Kernel& Setup::kernel(const std::string& name) {
  auto found = kernels.find(name);
  if (found == kernels.end()) {
    found = kernels.emplace(name, context.kernel(name, ProgramSource::bend_batch(), "")).first;
  }
  return found->second;
}

double event_seconds(const cl::Event& event) { return span_seconds(event, event); }

double span_seconds(const cl::Event& first, const cl::Event& last) {
  check_cl(last.wait(), "clWaitForEvents");
  const cl_ulong start = first.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = last.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-9;
}

double written_bytes(const BatchLayout& layout) {
  return static_cast<double>(layout.plane_stride * layout.instance_count *
                             layout.bytes_per_vertex());
}

void set_counters(benchmark::State& state, const BatchLayout& layout, double seconds) {
  const double vertices = static_cast<double>(layout.vertex_count * layout.instance_count);
  const auto rate = benchmark::Counter::kIsIterationInvariantRate;
  state.counters["vertices/s"] = benchmark::Counter(vertices, rate);
  state.counters["bytes/s"] = benchmark::Counter(written_bytes(layout), rate);  // SI: 1 G = 1e9
  state.counters["instances"] = static_cast<double>(layout.instance_count);
  state.counters["vertices"] = static_cast<double>(layout.vertex_count);
  const auto& write_only = Setup::get().write_only_bytes_per_second;
  const auto found = write_only.find({layout.instance_count, layout.normal_format});
  if (found != write_only.end() && seconds > 0.0) {
    const double bytes_per_second =
        written_bytes(layout) * static_cast<double>(state.iterations()) / seconds;
    state.counters["write_fraction"] = bytes_per_second / found->second;
  }
}

}  // namespace finflex::bench

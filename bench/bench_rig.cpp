// A rigged fish (the shipped rig of the benchmark mesh: FINFLEX_RIG, default
// data/rigs/blub.rig.json) on the fused path and on the multi-pass path.
#include <cmath>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

// Every parameter swinging through half its range, out of phase per instance.
RigParameters swimming_parameters(const Rig& rig, std::size_t instances) {
  RigParameters values(rig, instances);
  set_parameters(values, [&rig](std::size_t i, std::size_t p, std::size_t k) {
    return static_cast<float>(0.5 * rig.parameters[p].limit *
                              std::sin(0.1 * static_cast<double>(i + 3 * (p + k))));
  });
  return values;
}

}  // namespace

void BM_Rig(benchmark::State& state, RigPath path) {
  DeviceModel& rig = Setup::get().rig();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = rig.batch(instances);
  const RigParameters values = swimming_parameters(rig.model.rig(), instances);
  const ClJob job = rig.job(values, batch, NormalMode::kRotate, path);
  std::vector<cl::Event> kernels;
  const double seconds = time_iterations(state, [&] {
    rig.deformer.enqueue(job, &kernels);
    return span_seconds(kernels.front(), kernels.back());
  });
  set_counters(state, batch.shape, seconds);
  // Bytes each vertex of each instance moves: its output written once (24 B; the rest
  // mesh is shared by all instances), and on the multi-pass path its intermediate
  // results written and read again (24 B each way per stage after its first).
  const PassReport passes = pass_report(rig.deformer, path);
  state.counters["passes"] = static_cast<double>(passes.passes);
  state.counters["bytes/vertex"] = 24.0 * (1.0 + passes.scratch_records_per_slot);
}

}  // namespace finflex::bench

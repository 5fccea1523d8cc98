// A rigged fish (the shipped rig of the benchmark mesh: FINFLEX_RIG, default
// data/rigs/blub.rig.json) on the fused path and on the multi-pass path.
#include <cmath>

#include "bench_support.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::bench {
namespace {

// Every parameter swinging through half its range, out of phase per instance.
RigParameters swimming_parameters(const Rig& rig, std::size_t instances) {
  RigParameters values(rig, instances);
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
      const RigParameter& parameter = rig.parameters[p];
      for (std::size_t k = 0; k < parameter.count; ++k) {
        values.values()[i * values.values_per_instance() + parameter.offset + k] =
            static_cast<float>(0.5 * parameter.limit *
                               std::sin(0.1 * static_cast<double>(i + 3 * (p + k))));
      }
    }
  }
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
  set_counters(state, batch.layout, seconds);
  // Bytes each vertex of each instance moves: its output written once (24 B; the rest
  // mesh is shared by all instances), and on the multi-pass path its intermediate
  // results written and read again (24 B each way per stage after its first).
  const bool fused = path == RigPath::kFused;
  state.counters["passes"] = fused ? 1.0 : static_cast<double>(internal::pass_count(rig.deformer));
  state.counters["bytes/vertex"] =
      24.0 * (1.0 + (fused ? 0.0 : internal::scratch_records_per_slot(rig.deformer)));
}

}  // namespace finflex::bench

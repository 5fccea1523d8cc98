// A rigged fish (the shipped rig of the benchmark mesh: FINFLEX_RIG, default
// data/rigs/blub.rig.json) on the fused path and on the multi-pass path.
#include <cmath>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

struct RigSetup {
  Rig rig;
  ClRigDeformer deformer;
  std::map<std::size_t, DeviceBatch> batches;

  static RigSetup& get() {
    Setup& setup = Setup::get();
    static RigSetup rig_setup{
        resolve_rig(load_rig_file(env_or("FINFLEX_RIG",
                                         std::string(FINFLEX_DATA_DIR) + "/rigs/blub.rig.json")),
                    setup.mesh),
        setup};
    return rig_setup;
  }

  RigSetup(Rig resolved, Setup& setup)
      : rig(std::move(resolved)), deformer(setup.context, setup.mesh, rig) {}

  DeviceBatch& batch(std::size_t instances) {
    auto found = batches.find(instances);
    if (found == batches.end())
      found = batches.emplace(instances, deformer.allocate(instances)).first;
    return found->second;
  }
};

// Every parameter swinging through half its range, out of phase per instance.
RigParameters swimming_parameters(const Rig& rig, std::size_t instances) {
  const std::vector<double> limits = rig_param_limits(rig);
  RigParameters values(rig, instances);
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t p = 0; p < rig.params.size(); ++p) {
      values.values()[i * rig.params.size() + p] =
          static_cast<float>(0.5 * limits[p] * std::sin(0.1 * static_cast<double>(i + 3 * p)));
    }
  }
  return values;
}

}  // namespace

void BM_Rig(benchmark::State& state, RigPath path) {
  RigSetup& setup = RigSetup::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = setup.batch(instances);
  const RigParameters values = swimming_parameters(setup.rig, instances);
  std::vector<cl::Event> kernels;
  const double seconds = time_frames(state, [&] {
    setup.deformer.enqueue(values, NormalMode::kRotate, batch, path, false, nullptr, &kernels);
    return span_seconds(kernels.front(), kernels.back());
  });
  set_counters(state, batch.layout, seconds);
  // Bytes each vertex of each instance moves: its output written once (24 B; the rest
  // mesh is shared by all instances), and on the multi-pass path its intermediate
  // results written and read again (24 B each way per stage after its first).
  const bool fused = path == RigPath::kFused;
  state.counters["passes"] = fused ? 1.0 : static_cast<double>(setup.deformer.pass_count());
  state.counters["bytes/vertex"] =
      24.0 * (1.0 + (fused ? 0.0 : setup.deformer.scratch_records_per_slot()));
}

}  // namespace finflex::bench

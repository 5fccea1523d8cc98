#include "bench_support.hpp"

namespace finflex::bench {

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : fallback;
}

DeviceBatch& DeviceModel::batch(std::size_t instances, NormalFormat format) {
  const auto key = std::make_pair(instances, format);
  auto found = batches.find(key);
  if (found == batches.end()) {
    found = batches.emplace(key, deformer.allocate(instances, format)).first;
  }
  return found->second;
}

ClJob DeviceModel::job(const RigParameters& values, DeviceBatch& batch, NormalMode normals,
                       RigPath path) const {
  return frame_job(values, batch, normals, path);
}

Setup& Setup::get() {
  static Setup setup;
  return setup;
}

DeviceModel& Setup::bend(BendMode mode) {
  std::unique_ptr<DeviceModel>& model = bends_[mode];
  if (!model) {
    model = std::make_unique<DeviceModel>(context, RiggedMesh::single_bend(mesh, frame, mode));
  }
  return *model;
}

DeviceModel& Setup::rig() {
  if (!rig_) {
    const std::string path =
        env_or("FINFLEX_RIG", std::string(FINFLEX_DATA_DIR) + "/rigs/blub.rig.json");
    rig_ = std::make_unique<DeviceModel>(context,
                                         RiggedMesh(mesh, resolve_rig(load_rig_file(path), mesh)));
  }
  return *rig_;
}

std::vector<float> baseline_bend_values(std::size_t instances, double x_max) {
  std::vector<float> m(instances);
  for (std::size_t i = 0; i < instances; ++i) {
    m[i] = static_cast<float>(max_abs_m(x_max) * (static_cast<double>(i % 17) / 8.0 - 1.0));
  }
  return m;
}

void set_baseline_counters(benchmark::State& state, std::size_t instances, double seconds) {
  BatchShape layout;
  layout.vertex_count = Setup::get().mesh.vertex_count();
  layout.instance_count = instances;
  layout.plane_stride = layout.vertex_count;
  set_counters(state, layout, seconds);
}

double written_bytes(const BatchShape& layout) {
  return static_cast<double>(layout.plane_stride * layout.instance_count *
                             layout.bytes_per_vertex());
}

void set_counters(benchmark::State& state, const BatchShape& layout, double seconds) {
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

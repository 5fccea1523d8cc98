// The whole-body bend next to a write-only kernel and a copy kernel of the same
// NDRange and output planes.
#include <chrono>

#include "bench_support.hpp"

namespace finflex::bench {

void BM_WriteOnly(benchmark::State& state, NormalFormat format, std::size_t per_item,
                  WriteValues values, std::size_t lanes, bool streaming) {
  Setup& setup = Setup::get();
  DeviceModel& bend = setup.bend(BendMode::kPaper);
  DeviceBatch& batch = bend.batch(static_cast<std::size_t>(state.range(0)), format);
  const KernelShape shape = kernel_shape(bend.deformer, batch, NormalMode::kRotate);
  if (per_item == 0) per_item = shape.instances_per_item;
  if (lanes == 0) lanes = shape.lanes;
  const double seconds = time_iterations(state, [&] {
    return event_seconds(enqueue_write_only(setup.context, batch, batch.shape.plane_stride,
                                            per_item, values, lanes, streaming));
  });
  // The reference of write_fraction: the fastest write-only shape measured writing the
  // device's default values (never uniform data on GPUs, which they may compress).
  if (values == WriteValues::kDeviceDefault) {
    double& reference = setup.write_only_bytes_per_second[{batch.shape.instance_count, format}];
    reference = std::max(
        reference, written_bytes(batch.shape) * static_cast<double>(state.iterations()) / seconds);
  }
  set_counters(state, batch.shape, 0.0);
  state.counters["per_item"] = static_cast<double>(per_item);
  state.counters["lanes"] = static_cast<double>(lanes);
  state.counters["streaming"] = lanes > 1 && streaming ? 1.0 : 0.0;
}

void BM_CopyRest(benchmark::State& state) {
  Setup& setup = Setup::get();
  DeviceBatch& batch = setup.bend(BendMode::kPaper).batch(static_cast<std::size_t>(state.range(0)));
  set_counters(state, batch.shape, time_iterations(state, [&] {
                 return event_seconds(enqueue_copy_rest(setup.context, setup.copy_source, batch));
               }));
}

void BM_Bend(benchmark::State& state, BendMode mode, NormalMode normals, NormalFormat format) {
  DeviceModel& bend = Setup::get().bend(mode);
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = bend.batch(instances, format);
  RigParameters m(bend.model, instances);
  const float limit = static_cast<float>(bend.model.rig().parameters[0].limit);
  for (std::size_t i = 0; i < instances; ++i) {
    m.values()[i] = limit * (static_cast<float>(i % 17) / 8.0f - 1.0f);
  }
  const ClJob job = bend.job(m, batch, normals);
  const double seconds =
      time_iterations(state, [&] { return event_seconds(bend.deformer.enqueue(job)); });
  set_counters(state, batch.shape, seconds);
}

// Host time of one frame's enqueue (parameter check, non-blocking upload, launch),
// without the device's work: each frame waits for the previous one to finish first.
void BM_HostOverhead(benchmark::State& state) {
  DeviceModel& bend = Setup::get().bend(BendMode::kPaper);
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = bend.batch(instances);
  RigParameters m(bend.model, instances);
  std::fill(m.values().begin(), m.values().end(), 0.1f);
  const ClJob job = bend.job(m, batch, NormalMode::kRotate);
  check_cl(bend.deformer.enqueue(job).wait(), "clWaitForEvents");
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const cl::Event done = bend.deformer.enqueue(job);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    check_cl(done.wait(), "clWaitForEvents");
  }
  state.counters["instances"] = static_cast<double>(instances);
}

}  // namespace finflex::bench

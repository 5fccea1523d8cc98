// The single-bend kernel next to a write-only kernel and a copy kernel of the same
// NDRange and output planes.
#include <chrono>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

// Times `kernel` (arguments set) over the batch's NDRange, as bend_batch runs.
double time_batch_kernel(benchmark::State& state, cl::Kernel& kernel, const BatchLayout& layout) {
  Setup& setup = Setup::get();
  return time_frames(state, [&] {
    cl::Event done;
    check_cl(setup.context.queue().enqueueNDRangeKernel(
                 kernel, cl::NullRange, cl::NDRange(layout.plane_stride, layout.instance_count),
                 cl::NDRange(ClDeformer::kLocalSize, 1), nullptr, &done),
             "clEnqueueNDRangeKernel");
    return event_seconds(done);
  });
}

}  // namespace

void BM_WriteOnly(benchmark::State& state, NormalFormat format, std::size_t per_item,
                  WriteValues values) {
  Setup& setup = Setup::get();
  DeviceBatch& batch = setup.batch(static_cast<std::size_t>(state.range(0)), format);
  const double seconds = time_frames(state, [&] {
    return event_seconds(enqueue_write_only(setup.context, batch, per_item, values));
  });
  // The reference of write_fraction: the fastest write-only shape measured writing the
  // device's default values (never uniform data on GPUs, which they may compress).
  if (values == WriteValues::kDeviceDefault) {
    double& reference = setup.write_only_bytes_per_second[{batch.layout.instance_count, format}];
    reference = std::max(
        reference, written_bytes(batch.layout) * static_cast<double>(state.iterations()) / seconds);
  }
  set_counters(state, batch.layout, 0.0);
  state.counters["per_item"] = static_cast<double>(
      per_item ? per_item : instances_per_work_item(setup.context.description(), format));
}

void BM_CopyRest(benchmark::State& state) {
  Setup& setup = Setup::get();
  DeviceBatch& batch = setup.batch(static_cast<std::size_t>(state.range(0)));
  cl::Kernel& kernel = setup.kernel("copy_rest");
  kernel.setArg(0, setup.copy_source);
  kernel.setArg(1, batch.positions);
  kernel.setArg(2, batch.normals);
  kernel.setArg(3, static_cast<cl_uint>(batch.layout.plane_stride));
  set_counters(state, batch.layout, time_batch_kernel(state, kernel, batch.layout));
}

void BM_Bend(benchmark::State& state, BendSettings settings, NormalFormat format) {
  Setup& setup = Setup::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = setup.batch(instances, format);
  std::vector<float> m(instances);
  const float limit = static_cast<float>(max_abs_m(setup.local.x_max));
  for (std::size_t i = 0; i < instances; ++i) {
    m[i] = limit * (static_cast<float>(i % 17) / 8.0f - 1.0f);
  }
  const double seconds =
      time_frames(state, [&] { return event_seconds(setup.deformer.enqueue(m, settings, batch)); });
  set_counters(state, batch.layout, seconds);
}

}  // namespace finflex::bench

namespace finflex::bench {

// Host time of one frame's enqueue (parameter check, non-blocking upload, launch),
// without the device's work: each frame waits for the previous one to finish first.
void BM_HostOverhead(benchmark::State& state) {
  Setup& setup = Setup::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  DeviceBatch& batch = setup.batch(instances);
  std::vector<float> m(instances, 0.1f);
  const BendSettings settings{BendMode::kPaper, NormalMode::kRotate};
  check_cl(setup.deformer.enqueue(m, settings, batch).wait(), "clWaitForEvents");
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const cl::Event done = setup.deformer.enqueue(m, settings, batch);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    check_cl(done.wait(), "clWaitForEvents");
  }
  state.counters["instances"] = static_cast<double>(instances);
}

}  // namespace finflex::bench

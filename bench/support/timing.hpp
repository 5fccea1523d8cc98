// Timing of OpenCL work for the benchmarks and `finflex bench`: device time from
// profiling events, medians, and the frame loop (a warm-up frame, then timed ones).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <type_traits>
#include <vector>

#include <CL/opencl.hpp>

namespace finflex::bench {

// Waits for `last` and returns the device seconds from the start of `first` to the
// end of `last` (a sequence of kernels on one in-order queue).
double span_seconds(const cl::Event& first, const cl::Event& last);
// One command's device seconds.
inline double event_seconds(const cl::Event& event) { return span_seconds(event, event); }

double median(std::vector<double> values);

struct FrameTimes {
  std::vector<double> device;  // kernel time per frame
  std::vector<double> host;    // wall time of the enqueue call (checks, upload, launches)
  std::vector<std::vector<double>> kernels;  // per frame, each kernel's own time
  std::vector<double> reference;  // per frame, the reference kernel run after it (if any)

  // Each kernel's median over the frames (kernels in launch order).
  std::vector<double> kernel_medians() const;
};

// enqueue(kernels), or enqueue(kernels, timed) where Enqueue takes it: `timed` is false
// for the frames time_frames does not time (the warm-up, the leads below), whose side
// figures a caller leaves out.
template <typename Enqueue>
void enqueue_frame(Enqueue& enqueue, std::vector<cl::Event>& kernels, bool timed) {
  if constexpr (std::is_invocable_v<Enqueue&, std::vector<cl::Event>&, bool>) {
    enqueue(kernels, timed);
  } else {
    enqueue(kernels);
  }
}

// Runs one warm-up frame (PoCL compiles per work-group shape), then `frames` timed
// ones. `prepare(frame)` sets the frame's parameters (not timed: that is the
// application's animation); `enqueue(kernels)` enqueues the frame and fills `kernels`
// with its kernels' events (timed on the host, then on the device; enqueue_frame).
// `ahead`: the host prepares and enqueues frame f + 1 before it waits for frame f, as a
// frame loop that runs ahead of the device does, so a frame's kernels are all queued
// before the first of them starts and the device never waits for the host between
// them (GPUs: a frame waited for one by one holds the gap between its driver's end
// and the launch of its deformation). Off, each frame is waited for before the next
// is prepared (CPUs: the host's work would share the cores the kernels run on).
// `reference`, when given and the frames do not run ahead: a kernel run after every
// frame (the warm-up's too), its time in `times.reference`, so that a frame and its
// reference see a shared machine in the same state. Each timed frame then follows an
// untimed one of the same parameters (its lead) and each timed reference an untimed
// reference, so that each starts from the state its own kind leaves, as when timed on
// its own (a frame of plain stores leaves dirty cache lines for the next kernel to
// write back).
template <typename Prepare, typename Enqueue>
FrameTimes time_frames(std::size_t frames, Prepare prepare, Enqueue enqueue, bool ahead = false,
                       const std::function<cl::Event()>& reference = {}) {
  FrameTimes times;
  const bool interleaved = reference && !ahead;
  std::vector<cl::Event> kernels, in_flight;
  auto record = [&times](const std::vector<cl::Event>& frame) {
    times.device.push_back(span_seconds(frame.front(), frame.back()));
    std::vector<double> own;
    for (const cl::Event& kernel : frame) own.push_back(event_seconds(kernel));
    times.kernels.push_back(own);
  };
  auto untimed_frame = [&] {
    enqueue_frame(enqueue, kernels, false);
    span_seconds(kernels.front(), kernels.back());
  };
  prepare(0);
  untimed_frame();
  if (interleaved) event_seconds(reference());
  for (std::size_t f = 1; f <= frames; ++f) {
    prepare(f);
    if (interleaved) untimed_frame();  // the lead
    const auto start = std::chrono::steady_clock::now();
    enqueue_frame(enqueue, kernels, true);
    const auto end = std::chrono::steady_clock::now();
    times.host.push_back(std::chrono::duration<double>(end - start).count());
    if (!ahead) {
      record(kernels);
      if (interleaved) {
        event_seconds(reference());  // the lead
        times.reference.push_back(event_seconds(reference()));
      }
      continue;
    }
    if (!in_flight.empty()) record(in_flight);
    in_flight = kernels;
  }
  if (!in_flight.empty()) record(in_flight);
  return times;
}

}  // namespace finflex::bench

// The user events of a Context's FrameGates, made ahead by a helper thread: making one
// cost a frame 6-7 us on NVIDIA's OpenCL (docs/results/2026-11-28_h100_swim_host_breakdown.txt),
// taking one made ahead costs a lock.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

#include <CL/opencl.hpp>

namespace finflex::detail {

class GateEvents {
 public:
  explicit GateEvents(const cl::Context& context);
  // Stops the helper; the events not taken (never waited for) are released.
  ~GateEvents();
  GateEvents(const GateEvents&) = delete;
  GateEvents& operator=(const GateEvents&) = delete;

  // A new user event: one made ahead, else one made now (kOpenCL on failure).
  cl::UserEvent take();
  // After a gate opened (its frame enqueued): wakes the helper, started the first time,
  // when fewer than kLow are ready, to make up to kReady: once every few frames, and
  // after a frame's commands are enqueued rather than among them.
  void top_up();

 private:
  static constexpr std::size_t kReady = 8;
  static constexpr std::size_t kLow = 4;
  void make_ahead();  // the helper's loop

  cl::Context context_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<cl::UserEvent> ready_;
  bool wanted_ = false;    // top_up() asked the helper for more
  bool stopping_ = false;  // the destructor runs
  std::thread helper_;     // started by the first top_up()
};

}  // namespace finflex::detail

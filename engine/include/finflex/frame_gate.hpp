// A gate that holds a frame's device work back until all of it is enqueued:
//
//   FrameGate gate(context);
//   driver.enqueue(inputs, dt, gate.wait_list());  // the frame's first command waits
//   deformer.enqueue(job);                          // in order after it, on the same queue
//   gate.open();                                    // all of it goes to the device at once
//
// Without it the device starts the frame's first kernel while the host is still
// enqueuing the next, and waits between the two for the launch; each enqueue also
// submits its command to the device as it comes. Behind a closed gate (an OpenCL user
// event) the commands only queue on the host, and open() hands them over together.
// A frame goes faster and the host's enqueue takes less time behind a gate
// (docs/benchmarks.md#choice-frame-gate).
//
// Nothing may wait for work behind a closed gate (a blocking read or map, finish(),
// an event's wait()): that would wait forever. Open it first. The destructor opens a
// gate still closed, so an exception between never leaves the queue waiting; so does
// the Context's destructor (which waits for its queues) for a gate that outlives it.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/context.hpp"
#include "finflex/export.hpp"

namespace finflex {
namespace detail {

// A gate's user event and whether it was opened, shared by the FrameGate and its
// Context: the Context drops the opened ones without asking the driver (a status query
// costs a few microseconds of a frame on NVIDIA's OpenCL).
struct GateState {
  cl::UserEvent event;
  std::atomic<bool> opened{false};
};

}  // namespace detail

class FINFLEX_API FrameGate {
 public:
  explicit FrameGate(Context& context);
  ~FrameGate();
  FrameGate(const FrameGate&) = delete;
  FrameGate& operator=(const FrameGate&) = delete;

  // The wait list for the frame's first commands: the gate (complete once open).
  const std::vector<cl::Event>* wait_list() const { return &wait_; }
  // Lets the work behind the gate run, and flushes the context's queue so that it
  // reaches the device now (a semaphore signal among it, which another API's wait
  // needs submitted first: finflex/external_outputs.hpp). Opening an open gate does
  // nothing.
  void open();
  bool is_open() const { return open_; }

 private:
  std::shared_ptr<detail::GateState> gate_;
  cl::CommandQueue queue_;
  std::vector<cl::Event> wait_;
  bool open_ = false;
};

}  // namespace finflex

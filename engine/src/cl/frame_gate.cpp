// FrameGate (finflex/frame_gate.hpp): an OpenCL user event the frame's first commands
// wait for.
#include "finflex/frame_gate.hpp"

#include "finflex/error.hpp"

namespace finflex {

FrameGate::FrameGate(Context& context) : queue_(context.queue()) {
  cl_int status = CL_SUCCESS;
  gate_ = std::make_shared<detail::GateState>();
  gate_->event = cl::UserEvent(context.context(), &status);
  check_cl(status, "clCreateUserEvent");
  wait_.push_back(gate_->event);
  context.track_gate(gate_);
}

// Whoever turns `opened` from false to true (this gate or its Context's destructor)
// sets the event's status, once.
FrameGate::~FrameGate() {
  if (open_ || gate_->opened.exchange(true)) return;
  gate_->event.setStatus(CL_COMPLETE);  // no throwing here: the status is ignored
}

void FrameGate::open() {
  if (open_) return;
  open_ = true;
  if (gate_->opened.exchange(true)) return;  // the Context's destructor opened it
  check_cl(gate_->event.setStatus(CL_COMPLETE), "clSetUserEventStatus");
  check_cl(queue_.flush(), "clFlush");
}

}  // namespace finflex

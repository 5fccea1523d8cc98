// FrameGate (finflex/frame_gate.hpp): an OpenCL user event the frame's first commands
// wait for.
#include "finflex/frame_gate.hpp"

#include "finflex/error.hpp"

namespace finflex {

FrameGate::FrameGate(Context& context) {
  cl_int status = CL_SUCCESS;
  gate_ = std::make_shared<detail::GateState>();
  gate_->event = cl::UserEvent(context.context(), &status);
  check_cl(status, "clCreateUserEvent");
  wait_.push_back(gate_->event);
  context.track_gate(gate_);
}

FrameGate::~FrameGate() {
  if (open_) return;
  gate_->event.setStatus(CL_COMPLETE);  // no throwing here: the status is ignored
  gate_->opened = true;
}

void FrameGate::open() {
  if (open_) return;
  open_ = true;
  const cl_int status = gate_->event.setStatus(CL_COMPLETE);
  gate_->opened = true;
  check_cl(status, "clSetUserEventStatus");
}

}  // namespace finflex

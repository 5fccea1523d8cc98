// FrameGate (finflex/frame_gate.hpp): an OpenCL user event the frame's first commands
// wait for.
#include "finflex/frame_gate.hpp"

#include "finflex/error.hpp"

namespace finflex {

FrameGate::FrameGate(Context& context) {
  cl_int status = CL_SUCCESS;
  gate_ = cl::UserEvent(context.context(), &status);
  check_cl(status, "clCreateUserEvent");
  wait_.push_back(gate_);
  context.track_gate(gate_);
}

FrameGate::~FrameGate() {
  if (!open_) gate_.setStatus(CL_COMPLETE);  // no throwing here: the status is ignored
}

void FrameGate::open() {
  if (open_) return;
  open_ = true;
  check_cl(gate_.setStatus(CL_COMPLETE), "clSetUserEventStatus");
}

}  // namespace finflex

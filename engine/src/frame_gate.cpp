// FrameGate (finflex/frame_gate.hpp): an OpenCL user event the frame's first commands
// wait for.
#include "finflex/frame_gate.hpp"

#include "finflex/error.hpp"
#include "gate_events.hpp"

namespace finflex {

FrameGate::FrameGate(Context& context) {
  gate_ = std::make_shared<detail::GateState>();
  gate_->event = context.gate_events_->take();
  events_ = context.gate_events_;
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
  // The next frames' events are made now, while this frame's thread is out of the
  // driver's calls.
  if (const std::shared_ptr<detail::GateEvents> events = events_.lock()) events->top_up();
}

}  // namespace finflex

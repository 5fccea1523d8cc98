// Frame gates (finflex::FrameGate): a frame's device work held back until all of it is
// enqueued.
#include "handles.hpp"

using finflex::c::create;
using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

extern "C" {

finflex_status finflex_frame_gate_create(finflex_context* context, finflex_frame_gate** gate) {
  return create(slot_of(context), gate, "gate", [&] {
    auto handle = std::make_unique<finflex_frame_gate>();
    handle->context = require(context, "context")->context;
    handle->gate = std::make_unique<finflex::FrameGate>(*handle->context);
    handle->event.event = handle->gate->wait_list()->front();
    handle->event_list[0] = &handle->event;
    return handle;
  });
}

finflex_event* const* finflex_frame_gate_event_list(finflex_frame_gate* gate) {
  return gate == nullptr ? nullptr : gate->event_list;
}

finflex_status finflex_frame_gate_open(finflex_frame_gate* gate) {
  return guarded(slot_of(gate), [&] { require(gate, "gate")->gate->open(); });
}

int finflex_frame_gate_is_open(const finflex_frame_gate* gate) {
  return gate != nullptr && gate->gate->is_open() ? 1 : 0;
}

void finflex_frame_gate_destroy(finflex_frame_gate* gate) { delete gate; }

const finflex_error* finflex_frame_gate_error(const finflex_frame_gate* gate) {
  return slot_of(gate);
}

}  // extern "C"

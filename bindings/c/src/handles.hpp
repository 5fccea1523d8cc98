// The C API's handles (finflex.h declares them opaque) and the one wrapper every
// function body runs in, which turns C++ exceptions into a status and an error record.
#pragma once

#include <exception>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <finflex/finflex.hpp>

#include "finflex.h"

struct finflex_error {
  finflex_status status = FINFLEX_OK;
  std::string message;
  std::string field;
};

struct finflex_context {
  std::shared_ptr<finflex::Context> context;
  mutable finflex_error error;
};

struct finflex_mesh {
  finflex::Mesh mesh;
  mutable finflex_error error;
};

struct finflex_rig {
  finflex::RigSpec spec;
  mutable finflex_error error;
};

struct finflex_model {
  std::shared_ptr<const finflex::RiggedMesh> model;
  mutable finflex_error error;
};

struct finflex_parameters {
  explicit finflex_parameters(finflex::RigParameters p) : values(std::move(p)) {}
  finflex::RigParameters values;
  mutable finflex_error error;
};

struct finflex_deformer {
  // The context and model outlive the deformer that refers to them.
  std::shared_ptr<finflex::Context> context;
  std::shared_ptr<const finflex::RiggedMesh> model;
  std::unique_ptr<finflex::ClDeformer> deformer;
  mutable finflex_error error;
};

struct finflex_batch {
  finflex::DeviceBatch batch;
  mutable finflex_error error;
};

struct finflex_event {
  cl::Event event;
  mutable finflex_error error;
};

struct finflex_frame_gate {
  std::shared_ptr<finflex::Context> context;  // outlives the gate's event
  std::unique_ptr<finflex::FrameGate> gate;
  finflex_event event;           // the gate's user event, for wait lists
  finflex_event* event_list[1];  // {&event}: finflex_frame_gate_event_list
  mutable finflex_error error;
};

struct finflex_swim_model {
  std::shared_ptr<const finflex::SwimModel> swim;
  mutable finflex_error error;
};

struct finflex_swim_driver {
  // The context and swim model outlive the driver that refers to them.
  std::shared_ptr<finflex::Context> context;
  std::shared_ptr<const finflex::SwimModel> swim;
  std::unique_ptr<finflex::ClSwimDriver> driver;
  mutable finflex_error error;
};

namespace finflex::c {

// The calling thread's last failure.
finflex_error& thread_error();

// Records a failure on `slot` (may be null) and on the thread; returns `status`.
finflex_status fail(finflex_error* slot, finflex_status status, std::string field,
                    std::string message);

finflex_status status_of(finflex::ErrorCode code);

// Throws kInvalidArgument "<name> is NULL" (field `name`) when `pointer` is null.
template <typename T>
T* require(T* pointer, const char* name) {
  if (pointer == nullptr) {
    throw finflex::Error(finflex::ErrorCode::kInvalidArgument, name,
                         std::string(name) + " is NULL");
  }
  return pointer;
}

// The error slot of a handle that may be null.
template <typename Handle>
finflex_error* slot_of(const Handle* handle) {
  return handle == nullptr ? nullptr : &handle->error;
}

// Runs `body`; a success clears `slot`, an exception is recorded there and on the
// thread, as finflex::Error's code, field and message (std::bad_alloc as
// FINFLEX_ERROR_OUT_OF_MEMORY, anything else as FINFLEX_ERROR_INTERNAL).
template <typename Body>
finflex_status guarded(finflex_error* slot, Body&& body) noexcept {
  try {
    std::forward<Body>(body)();
    if (slot != nullptr) *slot = finflex_error{};
    return FINFLEX_OK;
  } catch (const finflex::Error& e) {
    return fail(slot, status_of(e.code()), e.field(), e.what());
  } catch (const std::bad_alloc&) {
    return fail(slot, FINFLEX_ERROR_OUT_OF_MEMORY, "", "out of host memory");
  } catch (const std::exception& e) {
    return fail(slot, FINFLEX_ERROR_INTERNAL, "", e.what());
  } catch (...) {
    return fail(slot, FINFLEX_ERROR_INTERNAL, "", "unknown exception");
  }
}

// Writes a new handle to *out once `make` succeeded; `out` itself is checked first.
template <typename Handle, typename Make>
finflex_status create(finflex_error* slot, Handle** out, const char* out_name, Make&& make) {
  return guarded(slot, [&] {
    require(out, out_name);
    std::unique_ptr<Handle> handle = std::forward<Make>(make)();
    *out = handle.release();
  });
}

}  // namespace finflex::c

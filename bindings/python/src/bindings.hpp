// The Python module's shared pieces: the objects it wraps and the functions that bind
// each part of the API (one file each).
#pragma once

#include <memory>
#include <string>

#include <nanobind/nanobind.h>

#include <finflex/finflex.hpp>

namespace finflex::python {

namespace nb = nanobind;

// A context, shared by the deformers made on it (they outlive the Python object).
struct PyContext {
  std::shared_ptr<Context> context;
};

// A model: the mesh with its rig, shared by its parameters and deformers.
struct PyModel {
  std::shared_ptr<const RiggedMesh> model;
};

// Per-instance parameter values of a model.
struct PyParameters {
  std::shared_ptr<const RiggedMesh> model;
  RigParameters values;
};

struct PyDeformer {
  std::shared_ptr<Context> context;
  std::shared_ptr<const RiggedMesh> model;
  std::unique_ptr<ClDeformer> deformer;
};

struct PyBatch {
  DeviceBatch batch;
};

struct PyEvent {
  cl::Event event;
  // Host time of the library's enqueue (ClDeformer::enqueue) inside the Python call
  // that made the event: the call's time minus this is the binding's overhead.
  double enqueue_seconds = 0.0;
};

// Throws finflex::Error (kInvalidArgument) naming `field`: raised in Python as
// finflex.Error.
[[noreturn]] void reject(const std::string& field, const std::string& message);

void bind_errors(nb::module_& m);
void bind_mesh(nb::module_& m);
void bind_model(nb::module_& m);
void bind_layout(nb::module_& m);
void bind_outputs(nb::module_& m);
void bind_device(nb::module_& m);
void bind_job(nb::module_& m);
void bind_frame(nb::module_& m);
void bind_swim(nb::module_& m);

}  // namespace finflex::python

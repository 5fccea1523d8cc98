// A frame's job from Python: described once (PyJob) or per call (Deformer.enqueue),
// enqueued by one function.
#pragma once

#include <string>
#include <vector>

#include "bindings.hpp"

namespace finflex::python {

// A job whose model, outputs, normals, clamp and path are set once.
struct PyJob {
  nb::object deformer;  // the PyDeformer and PyBatch the job refers to, kept alive
  nb::object batch;
  ClJob job;
};

// The job of `deformer` into `batch` (normals, clamp, path parsed: errors name them).
ClJob describe_frames(PyBatch& batch, const std::string& normals, bool clamp,
                      const std::string& path);

// The events of `wait`: a sequence of finflex.Event, or None.
std::vector<cl::Event> wait_events(nb::handle wait);

// Enqueues `job` after the events of `wait`, with the GIL released.
PyEvent enqueue_job(PyDeformer& deformer, ClJob& job, nb::handle wait);

// Points `job` at `parameters` (checked: ParameterArgument), then enqueue_job.
PyEvent enqueue_frame(PyDeformer& deformer, ClJob& job, nb::handle parameters, nb::handle wait);

}  // namespace finflex::python

// finflex.Job: a deformer's job for one batch, described once (normals, clamp, path)
// and enqueued every frame with new parameters: the frame loop's call, with the least
// work per call (the C++ ClJob reused the same way).
#include <chrono>

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"
#include "job.hpp"

namespace finflex::python {

std::vector<cl::Event> wait_events(nb::handle wait) {
  std::vector<cl::Event> events;
  if (!wait.is_none()) {
    for (nb::handle e : wait) events.push_back(nb::cast<const PyEvent&>(e).event);
  }
  return events;
}

PyEvent enqueue_frame(PyDeformer& deformer, ClJob& job, nb::handle parameters, nb::handle wait) {
  const ParameterArgument rows(parameters, *deformer.model);
  job.parameters = rows.view();
  job.instances = job.parameters.instance_count;
  return enqueue_job(deformer, job, wait);
}

PyEvent enqueue_job(PyDeformer& deformer, ClJob& job, nb::handle wait) {
  const std::vector<cl::Event> events = wait_events(wait);
  job.wait = events.empty() ? nullptr : &events;
  PyEvent done;
  {
    nb::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    done.event = deformer.deformer->enqueue(job);
    done.enqueue_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  job.wait = nullptr;
  return done;
}

ClJob describe_frames(PyBatch& batch, const std::string& normals, bool clamp,
                      const std::string& path) {
  ClJob job;
  job.normals = parse_normal_mode(normals);
  job.clamp = clamp;
  job.path = parse_rig_path(path);
  job.outputs = &batch.batch;
  return job;
}

void bind_job(nb::module_& m) {
  nb::class_<PyJob>(m, "Job",
                    "A deformer's frames into one batch (Deformer.job): normals, clamp and "
                    "path fixed, parameters new every frame. Keeps its deformer and batch.")
      .def(
          "enqueue",
          [](PyJob& j, nb::handle parameters, nb::handle wait) {
            return enqueue_frame(nb::cast<PyDeformer&>(j.deformer), j.job, parameters, wait);
          },
          nb::arg("parameters"), nb::arg("wait") = nb::none(),
          nb::sig("def enqueue(self, parameters: numpy.typing.NDArray[numpy.float32] | "
                  "Parameters, wait: collections.abc.Sequence[Event] | None = None) -> Event"),
          "Deformer.enqueue with this job's batch and settings.")
      .def_prop_ro(
          "batch",
          [](const PyJob& j) -> const PyBatch& { return nb::cast<const PyBatch&>(j.batch); },
          nb::rv_policy::reference_internal, "The batch the job writes.");
}

}  // namespace finflex::python

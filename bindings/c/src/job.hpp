// A finflex_job as the C++ job both backends run (finflex/job.hpp).
#pragma once

#include "handles.hpp"

namespace finflex::c {

// Copies the job's fields into `out` (not its outputs or path). Throws
// kInvalidArgument naming "job" when it is null, "job.normals" or "job.path" when
// they are not one of their enum's values.
template <typename Outputs>
void fill_job(const finflex_job* job, finflex::BasicDeformJob<Outputs>& out);

finflex::NormalMode normal_mode(finflex_normal_mode mode);
finflex::RigPath rig_path(finflex_rig_path path);

// The events of a wait list (`count` handles at `wait`; "wait" or "wait[k]" named when
// null).
std::vector<cl::Event> wait_events(finflex_event* const* wait, std::size_t count);

// Enqueues through `enqueue` (returning the cl::Event of the work) and hands the event
// to *done when `done` is not null; the handle is allocated first, so nothing is
// enqueued when that fails.
template <typename Enqueue>
void enqueue_with_event(finflex_event** done, Enqueue&& enqueue) {
  std::unique_ptr<finflex_event> handle =
      done == nullptr ? nullptr : std::make_unique<finflex_event>();
  cl::Event event = std::forward<Enqueue>(enqueue)();
  if (done != nullptr) {
    handle->event = std::move(event);
    *done = handle.release();
  }
}

template <typename Outputs>
void fill_job(const finflex_job* job, finflex::BasicDeformJob<Outputs>& out) {
  require(job, "job");
  out.instances = job->instance_count;
  out.parameters =
      finflex::ParameterView{job->parameters, job->instance_count, job->parameter_stride};
  out.normals = normal_mode(job->normals);
  out.clamp = job->clamp != 0;
  rig_path(job->path);  // checked for every backend; ClJob::path is set by its caller
}

}  // namespace finflex::c

// A finflex_job as the C++ job both backends run (finflex/job.hpp).
#pragma once

#include "handles.hpp"

namespace finflex::c {

// Copies the job's fields into `out` (not its model or outputs). Throws
// kInvalidArgument naming "job" when it is null, "job.normals" or "job.path" when
// they are not one of their enum's values.
template <typename Outputs, typename Event, typename Buffer>
void fill_job(const finflex_job* job, finflex::BasicDeformJob<Outputs, Event, Buffer>& out);

finflex::NormalMode normal_mode(finflex_normal_mode mode);
finflex::RigPath rig_path(finflex_rig_path path);

template <typename Outputs, typename Event, typename Buffer>
void fill_job(const finflex_job* job, finflex::BasicDeformJob<Outputs, Event, Buffer>& out) {
  require(job, "job");
  out.parameters =
      finflex::ParameterView{job->parameters, job->instance_count, job->parameter_stride};
  out.normals = normal_mode(job->normals);
  out.clamp = job->clamp != 0;
  out.path = rig_path(job->path);
}

}  // namespace finflex::c

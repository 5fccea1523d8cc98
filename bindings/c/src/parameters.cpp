// Per-instance parameter values, and the job's defaults.
#include "handles.hpp"

using finflex::c::create;
using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

namespace {

finflex::RigParameters& values_of(finflex_parameters* parameters) {
  return require(parameters, "parameters")->values;
}

}  // namespace

extern "C" {

finflex_status finflex_parameters_create(const finflex_model* model, size_t instance_count,
                                         finflex_parameters** parameters) {
  return create(slot_of(model), parameters, "parameters", [&] {
    const finflex::RiggedMesh& m = *require(model, "model")->model;
    return std::make_unique<finflex_parameters>(finflex::RigParameters(m, instance_count));
  });
}

void finflex_parameters_destroy(finflex_parameters* parameters) { delete parameters; }

const finflex_error* finflex_parameters_error(const finflex_parameters* parameters) {
  return slot_of(parameters);
}

size_t finflex_parameters_instance_count(const finflex_parameters* parameters) {
  return parameters == nullptr ? 0 : parameters->values.instance_count();
}

finflex_status finflex_parameters_set(finflex_parameters* parameters, size_t instance,
                                      const char* name, float value) {
  return guarded(slot_of(parameters),
                 [&] { values_of(parameters).set(instance, require(name, "name"), value); });
}

finflex_status finflex_parameters_set_values(finflex_parameters* parameters, size_t instance,
                                             const char* name, const float* values, size_t count) {
  return guarded(slot_of(parameters), [&] {
    finflex::RigParameters& p = values_of(parameters);
    require(name, "name");
    if (count > 0) require(values, "values");
    p.set(instance, name, std::vector<float>(values, values + count));
  });
}

finflex_status finflex_parameters_get(finflex_parameters* parameters, size_t instance,
                                      const char* name, float* value) {
  return guarded(slot_of(parameters), [&] {
    const finflex::RigParameters& p = values_of(parameters);
    require(name, "name");
    require(value, "value");
    std::size_t index = p.parameters().size();
    for (std::size_t k = 0; k < p.parameters().size(); ++k) {
      if (p.parameters()[k].name == name) index = k;
    }
    if (index == p.parameters().size()) {
      std::string known;
      for (const finflex::RigParameter& k : p.parameters())
        known += (known.empty() ? "" : ", ") + k.name;
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, name,
                           "parameter '" + std::string(name) +
                               "' is not in the rig (its parameters: " + known + ")");
    }
    *value = p.get(instance, index);
  });
}

float* finflex_parameters_data(finflex_parameters* parameters) {
  return parameters == nullptr ? nullptr : parameters->values.values().data();
}

finflex_status finflex_parameters_view(finflex_parameters* parameters, finflex_job* job) {
  return guarded(slot_of(parameters), [&] {
    const finflex::ParameterView view = values_of(parameters).view();
    require(job, "job");
    job->parameters = view.data;
    job->instance_count = view.instance_count;
    job->parameter_stride = view.stride;
  });
}

void finflex_job_init(finflex_job* job) {
  if (job == nullptr) return;
  job->parameters = nullptr;
  job->instance_count = 0;
  job->parameter_stride = 0;
  job->normals = FINFLEX_NORMALS_ROTATE;
  job->clamp = 0;
  job->path = FINFLEX_PATH_AUTO;
}

}  // extern "C"

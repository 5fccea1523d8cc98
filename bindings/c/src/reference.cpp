// The CPU reference into host outputs, and host outputs as meshes.
#include "host_outputs.hpp"
#include "job.hpp"

using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

extern "C" {

finflex_status finflex_reference_deform(finflex_model* model, const finflex_job* job,
                                        const finflex_host_outputs* outputs) {
  return guarded(slot_of(model), [&] {
    const finflex::RiggedMesh& m = *require(model, "model")->model;
    finflex::DeformedBatch<double> deformed;
    finflex::ReferenceJob reference;
    reference.outputs = &deformed;
    finflex::c::fill_job(job, reference);
    reference.validate(m);
    finflex::c::check_outputs(outputs, job->instance_count, m.vertex_count(),
                              m.mesh().has_tangents());
    finflex::run_reference(m, reference);
    finflex::c::store_outputs(deformed, *outputs);
  });
}

finflex_status finflex_model_instance_mesh(finflex_model* model,
                                           const finflex_host_outputs* outputs,
                                           size_t instance_count, size_t instance,
                                           finflex_mesh** mesh) {
  return finflex::c::create(slot_of(model), mesh, "mesh", [&] {
    const finflex::Mesh& rest = require(model, "model")->model->mesh();
    finflex::c::check_outputs(outputs, instance_count, rest.vertex_count(), rest.has_tangents());
    if (instance >= instance_count) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "instance",
                           "instance = " + std::to_string(instance) +
                               " is out of range: the outputs hold " +
                               std::to_string(instance_count) + " instances");
    }
    if (outputs->positions.data == nullptr) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "outputs.positions.data",
                           "outputs.positions.data is NULL: a mesh needs positions");
    }
    auto handle = std::make_unique<finflex_mesh>();
    finflex::Mesh& m = handle->mesh;
    m = rest;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      m.positions[v] = finflex::c::load_element(outputs->positions, instance, v);
      if (outputs->normals.data != nullptr) {
        m.normals[v] = finflex::c::load_element(outputs->normals, instance, v);
      }
      if (outputs->tangents.data != nullptr) {
        m.tangents[v] =
            glm::vec4(finflex::c::load_element(outputs->tangents, instance, v), rest.tangents[v].w);
      }
    }
    finflex::validate_mesh(m);
    return handle;
  });
}

}  // extern "C"

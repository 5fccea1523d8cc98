// The C++ library's answers for the C API test.
#include "oracle.h"

#include <cstdio>
#include <exception>
#include <vector>

#include <finflex/finflex.hpp>

extern "C" int oracle_reference(const char* mesh_path, const char* rig_path, size_t instances,
                                const float* values, int jacobian_normals, float* positions,
                                float* normals) {
  try {
    const finflex::Mesh mesh = finflex::load_mesh(mesh_path);
    const finflex::RiggedMesh model =
        rig_path == nullptr
            ? finflex::RiggedMesh::single_bend(mesh, finflex::find_body_frame(mesh),
                                               finflex::BendMode::kExact)
            : finflex::RiggedMesh(mesh,
                                  finflex::resolve_rig(finflex::load_rig_file(rig_path), mesh));
    finflex::RigParameters p(model, instances);
    std::copy(values, values + instances * model.values_per_instance(), p.values().begin());
    const finflex::DeformedBatch<double> out = finflex::run_reference(
        model, p,
        jacobian_normals != 0 ? finflex::NormalMode::kJacobian : finflex::NormalMode::kRotate);
    const std::size_t vertices = mesh.vertex_count();
    for (std::size_t i = 0; i < instances; ++i) {
      for (std::size_t v = 0; v < vertices; ++v) {
        const glm::vec3 position(out.position(i, v));
        const glm::vec3 normal(out.normal(i, v));
        for (int c = 0; c < 3; ++c) {
          positions[(i * vertices + v) * 3 + c] = position[c];
          normals[(i * vertices + v) * 3 + c] = normal[c];
        }
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oracle: %s\n", e.what());
    return 1;
  }
}

extern "C" int oracle_swim(const char* mesh_path, const char* rig_path, size_t fish,
                           const float* lengths, const float* inputs, size_t frames,
                           float* positions, float* normals) {
  try {
    const finflex::Mesh mesh = finflex::load_mesh(mesh_path);
    const finflex::SwimModel swim(
        finflex::RiggedMesh(mesh, finflex::resolve_rig(finflex::load_rig_file(rig_path), mesh)));
    std::vector<finflex::SwimInput> frame;
    finflex::swim_inputs_from_rows(inputs, fish, frame);
    finflex::Context context;
    finflex::ClSwimDriver driver(context, swim, std::vector<float>(lengths, lengths + fish));
    finflex::ClDeformer deformer(context, swim.model());
    finflex::DeviceBatch batch = deformer.allocate(fish);
    finflex::ClJob job;
    job.instances = fish;
    job.device.parameters = &driver.parameter_buffer();
    job.device.placements = &driver.placement_buffer();
    job.outputs = &batch;
    for (std::size_t f = 0; f < frames; ++f) {
      driver.enqueue(frame, 1.0f / 30.0f);
      deformer.enqueue(job);
    }
    const finflex::DeformedBatch<float> out = deformer.read(batch);
    const std::size_t vertices = mesh.vertex_count();
    for (std::size_t i = 0; i < fish; ++i) {
      for (std::size_t v = 0; v < vertices; ++v) {
        for (int c = 0; c < 3; ++c) {
          positions[(i * vertices + v) * 3 + c] = out.position(i, v)[c];
          normals[(i * vertices + v) * 3 + c] = out.normal(i, v)[c];
        }
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oracle_swim: %s\n", e.what());
    return 1;
  }
}

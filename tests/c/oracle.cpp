// The C++ library's answers for the C API test.
#include "oracle.h"

#include <cstdio>
#include <exception>

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

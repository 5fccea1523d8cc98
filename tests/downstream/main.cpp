// Bends a small synthetic mesh with the installed library on the default device and
// checks it against the reference. Exit 0 on agreement.
#include <cstdio>

#include <finflex/finflex.hpp>

int main() {
  finflex::Mesh mesh;
  mesh.positions = {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.1f, 0.05f}};
  mesh.indices = {0, 1, 2};
  finflex::compute_vertex_normals(mesh);
  const finflex::LocalMesh local = finflex::make_local_mesh(mesh, finflex::BodyFrame::identity());

  finflex::Context context;
  finflex::ClDeformer deformer(context, local);
  finflex::DeviceBatch batch = deformer.allocate(2);
  const std::vector<float> m = {0.5f, -0.9f};
  const finflex::BendSettings settings{finflex::BendMode::kExact, finflex::NormalMode::kJacobian};
  deformer.enqueue(m, settings, batch);
  const finflex::DeformedBatch<float> device = deformer.read(batch);
  const finflex::DeformedBatch<double> reference =
      finflex::ReferenceDeformer(local).run(m, settings);
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const double error =
          glm::length(glm::dvec3(device.position(i, v)) - reference.position(i, v));
      if (error > 1e-5) {
        std::printf("instance %zu vertex %zu differs by %g\n", i, v, error);
        return 1;
      }
    }
  }
  std::printf("downstream: %s agrees with the reference\n",
              context.description().device_name.c_str());
  return 0;
}

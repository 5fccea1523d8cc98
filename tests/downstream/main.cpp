// Bends a small synthetic mesh with the installed library on the default device and
// checks it against the reference: the same job on both backends. Exit 0 on agreement.
#include <cstdio>

#include <finflex/finflex.hpp>

int main() {
  finflex::Mesh mesh;
  mesh.positions = {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.1f, 0.05f}};
  mesh.indices = {0, 1, 2};
  finflex::compute_vertex_normals(mesh);
  const finflex::RiggedMesh model = finflex::RiggedMesh::single_bend(
      mesh, finflex::BodyFrame::identity(), finflex::BendMode::kExact);
  finflex::RigParameters m(model, 2);
  m.set(0, "m", 0.5f);
  m.set(1, "m", -0.9f);

  finflex::Context context;
  finflex::ClDeformer deformer(context, model);
  finflex::DeviceBatch batch = deformer.allocate(2);
  finflex::ClJob job;
  job.instances = m.instance_count();
  job.parameters = m.view();
  job.normals = finflex::NormalMode::kJacobian;
  job.outputs = &batch;
  deformer.enqueue(job);
  const finflex::DeformedBatch<float> device = deformer.read(batch);

  finflex::DeformedBatch<double> reference;
  finflex::ReferenceJob reference_job;
  reference_job.instances = m.instance_count();
  reference_job.parameters = m.view();
  reference_job.normals = finflex::NormalMode::kJacobian;
  reference_job.outputs = &reference;
  finflex::run_reference(model, reference_job);
  for (std::size_t i = 0; i < 2; ++i) {
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

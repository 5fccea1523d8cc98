#include "reference/stage_walk.hpp"

#include <algorithm>
#include <cmath>

namespace finflex::detail {

Vertex rest_vertex(const Mesh& mesh, std::size_t v) {
  Vertex x;
  x.position = glm::dvec3(mesh.positions[v]);
  x.normal = glm::normalize(glm::dvec3(mesh.normals[v]));
  if (mesh.has_tangents()) x.tangent = glm::normalize(glm::dvec3(glm::vec3(mesh.tangents[v])));
  return x;
}

Vertex deform_vertex(const RiggedMesh& model, std::size_t v, const double* row, NormalMode normals,
                     PathConditioning* conditioning) {
  const Rig& rig = model.rig();
  Vertex x = rest_vertex(model.mesh(), v);
  for (const StageRef& ref : model.paths()[model.component_of_vertex()[v]]) {
    const RigStage& stage = rig.stage(ref);
    const BodyFrame& f = stage.frame;
    // Into the stage's frame by (2), the secant transform, back out by (2).
    const Vertex local{f.point_to_local(x.position), f.vector_to_local(x.normal),
                       f.vector_to_local(x.tangent)};
    const SecantSample sample = stage.deformer->secant(
        local.position.x, row + rig.parameters[stage.param].offset, stage.options, stage.geometry);
    const Vertex moved = apply_secant(local, sample, normals);
    x = {f.point_to_mesh(moved.position), f.vector_to_mesh(moved.normal),
         f.vector_to_mesh(moved.tangent)};
    if (conditioning) {
      const double zk = local.position.z * sample.curvature;
      ++conditioning->stages;
      conditioning->near_fold = conditioning->near_fold || std::fabs(1.0 - zk) < kFoldMargin;
      conditioning->folded = conditioning->folded || zk >= 1.0;
      if (sample.near_limit) {
        conditioning->near_limit = true;
        conditioning->near_limit_z =
            std::max(conditioning->near_limit_z, std::fabs(local.position.z) * f.length);
      }
    }
  }
  return x;
}

}  // namespace finflex::detail

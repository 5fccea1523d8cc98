// The rig's CPU reference: METHOD.md section 2 applied literally. For every vertex,
// the stages of its component's chain, then of its parent's, ... then of the root's;
// each stage: into its frame by (2), the deformer, out of the frame by (2).
#include "finflex/error.hpp"
#include "finflex/rig_deformer.hpp"
#include "spine_reference.hpp"

namespace finflex {
namespace {

detail::SpineSample stage_spine(const RigStage& stage, double x, double value) {
  if (stage.deformer == DeformerKind::kHinge) return detail::hinge_spine(x, value, stage.width);
  return stage.mode == BendMode::kExact ? detail::exact_spine(x, value)
                                        : detail::paper_spine(x, value);
}

LocalVertex apply_stage(const RigStage& stage, const LocalVertex& vertex, double value,
                        NormalMode normals) {
  const BodyFrame& f = stage.frame;
  LocalVertex local{f.point_to_local(vertex.position), f.vector_to_local(vertex.normal),
                    f.vector_to_local(vertex.tangent)};
  const LocalVertex bent =
      detail::apply_spine(local, stage_spine(stage, local.position.x, value), normals);
  return {f.point_to_mesh(bent.position), f.vector_to_mesh(bent.normal),
          f.vector_to_mesh(bent.tangent)};
}

}  // namespace

RigReference::RigReference(const Mesh& mesh, const Rig& rig)
    : mesh_(mesh), rig_(rig), limits_(rig_param_limits(rig)) {
  validate_mesh(mesh_);
  component_of_vertex_.assign(mesh_.vertex_count(), rig_.components.size());
  for (std::size_t c = 0; c < rig_.components.size(); ++c) {
    for (std::uint32_t v : rig_.components[c].vertices) component_of_vertex_[v] = c;
  }
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (component_of_vertex_[v] == rig_.components.size()) {
      throw Error(ErrorCode::kInvalidArgument, "rig",
                  "vertex " + std::to_string(v) + " belongs to no component of the rig");
    }
  }
}

DeformedBatch<double> RigReference::run(const RigParameters& parameters, NormalMode normals,
                                        bool clamp) const {
  std::vector<float> values;
  check_rig_params_into(rig_, limits_, parameters, clamp, values);
  BatchLayout layout;
  layout.vertex_count = mesh_.vertex_count();
  layout.instance_count = parameters.instance_count();
  layout.plane_stride = padded_plane_stride(layout.vertex_count);
  layout.tangents = mesh_.has_tangents();
  DeformedBatch<double> out;
  out.resize(layout);
  const std::size_t count = rig_.params.size();
  for (std::size_t i = 0; i < layout.instance_count; ++i) {
    for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
      LocalVertex x{glm::dvec3(mesh_.positions[v]), glm::normalize(glm::dvec3(mesh_.normals[v])),
                    glm::dvec3(0.0)};
      if (mesh_.has_tangents())
        x.tangent = glm::normalize(glm::dvec3(glm::vec3(mesh_.tangents[v])));
      for (const auto& [component, stage] : rig_.path(component_of_vertex_[v])) {
        const RigStage& s = rig_.components[component].chain[stage];
        x = apply_stage(s, x, values[i * count + s.param], normals);
      }
      out.scatter(out.positions, i, v, x.position);
      out.scatter(out.normals, i, v, x.normal);
      if (mesh_.has_tangents()) out.scatter(out.tangents, i, v, x.tangent);
    }
  }
  return out;
}

}  // namespace finflex

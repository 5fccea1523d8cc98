#include "finflex/reference_deformer.hpp"

#include "spine_reference.hpp"

namespace finflex {
LocalVertex bend_local_vertex(const LocalVertex& rest, double m, const BendSettings& settings) {
  const double x = rest.position.x;
  return detail::apply_spine(
      rest,
      settings.mode == BendMode::kExact ? detail::exact_spine(x, m) : detail::paper_spine(x, m),
      settings.normals);
}

BatchLayout ReferenceDeformer::layout(std::size_t instances) const {
  BatchLayout layout;
  layout.vertex_count = mesh_.vertex_count();
  layout.instance_count = instances;
  layout.plane_stride = padded_plane_stride(layout.vertex_count);
  layout.tangents = mesh_.has_tangents();
  return layout;
}

DeformedBatch<double> ReferenceDeformer::run(const std::vector<float>& m,
                                             const BendSettings& settings, bool clamp) const {
  const std::vector<float> params = checked_bend_params(m, mesh_.x_max, clamp);
  DeformedBatch<double> out;
  out.resize(layout(params.size()));
  const BodyFrame& frame = mesh_.frame;
  for (std::size_t i = 0; i < params.size(); ++i) {
    for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
      LocalVertex rest{mesh_.positions[v], mesh_.normals[v], glm::dvec3(0.0)};
      if (mesh_.has_tangents()) rest.tangent = glm::dvec3(mesh_.tangents[v]);
      const LocalVertex bent = bend_local_vertex(rest, params[i], settings);
      out.scatter(out.positions, i, v, frame.point_to_mesh(bent.position));
      out.scatter(out.normals, i, v, frame.vector_to_mesh(bent.normal));
      if (mesh_.has_tangents()) out.scatter(out.tangents, i, v, frame.vector_to_mesh(bent.tangent));
    }
  }
  return out;
}

}  // namespace finflex

// The CPU reference backend (finflex/reference.hpp): every vertex of every instance
// through its path of stages, literally, in double precision.
#include "finflex/reference.hpp"

#include <string>
#include <vector>

#include "finflex/error.hpp"

#include "model/parameter_checks.hpp"
#include "model/placement_transform.hpp"
#include "reference/stage_walk.hpp"

namespace finflex {

void run_reference(const RiggedMesh& model, const ReferenceJob& job) {
  job.validate(model);
  const std::size_t per_instance = model.values_per_instance();
  const std::size_t instances = job.instances;
  std::vector<float> values(instances * per_instance);
  detail::ParameterChecker(model.rig()).check(job.rows(), job.clamp, values.data());

  BatchShape layout;
  layout.vertex_count = model.vertex_count();
  layout.instance_count = instances;
  layout.plane_stride = padded_plane_stride(layout.vertex_count);
  layout.tangents = model.mesh().has_tangents();
  DeformedBatch<double> out;
  out.resize(layout);
  std::vector<detail::PlacementTransform> placed;
  if (job.placements) {
    const BodyFrame& body = model.rig().components.front().frame;
    for (std::size_t i = 0; i < instances; ++i) {
      try {
        placed.push_back(detail::placement_transform(job.placements[i], body));
      } catch (const Error& e) {
        const std::string field = "job.placements[" + std::to_string(i) + "]";
        throw Error(e.code(), field, field + ": " + e.what());
      }
    }
  }
  std::vector<double> row(per_instance);
  for (std::size_t i = 0; i < instances; ++i) {
    std::copy(values.begin() + static_cast<std::ptrdiff_t>(i * per_instance),
              values.begin() + static_cast<std::ptrdiff_t>((i + 1) * per_instance), row.begin());
    for (std::size_t v = 0; v < layout.vertex_count; ++v) {
      detail::Vertex x = detail::deform_vertex(model, v, row.data(), job.normals);
      if (!placed.empty()) {
        x = {placed[i].point(x.position), placed[i].direction(x.normal),
             placed[i].direction(x.tangent)};
      }
      out.scatter(out.positions, i, v, x.position);
      out.scatter(out.normals, i, v, x.normal);
      if (layout.tangents) out.scatter(out.tangents, i, v, x.tangent);
    }
  }
  *job.outputs = std::move(out);
}

DeformedBatch<double> run_reference(const RiggedMesh& model, const RigParameters& parameters,
                                    NormalMode normals, bool clamp, const Placement* placements) {
  DeformedBatch<double> out;
  ReferenceJob job;
  job.instances = parameters.instance_count();
  job.parameters = parameters.view();
  job.normals = normals;
  job.clamp = clamp;
  job.placements = placements;
  job.outputs = &out;
  run_reference(model, job);
  return out;
}

}  // namespace finflex

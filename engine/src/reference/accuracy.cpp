#include "finflex/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "reference/stage_walk.hpp"

namespace finflex {
namespace {

constexpr double kPositionBound = 4e-6;  // times (|origin| + s_x) of the root's frame
constexpr double kNormalBound = 2e-5;
constexpr double kNearLimitBound = 2e-3;

// Instance i's parameter row as doubles.
std::vector<double> row_of(const RiggedMesh& model, const ParameterView& parameters,
                           std::size_t i) {
  const std::size_t count = model.values_per_instance();
  const std::size_t stride = parameters.stride ? parameters.stride : count;
  std::vector<double> row(count);
  for (std::size_t k = 0; k < count; ++k) row[k] = parameters.data[i * stride + k];
  return row;
}

}  // namespace

AccuracyReport compare_to_reference(const RiggedMesh& model, const ParameterView& parameters,
                                    NormalMode normals, const DeformedBatch<float>& device,
                                    const DeformedBatch<double>& reference,
                                    const Placement* placements) {
  const BatchShape& a = device.shape;
  const BatchShape& b = reference.shape;
  const std::size_t instances = parameters.instance_count;
  if (a.vertex_count != model.vertex_count() || b.vertex_count != model.vertex_count() ||
      a.instance_count != instances || b.instance_count != instances || a.tangents != b.tangents) {
    throw Error(ErrorCode::kInvalidArgument, "device",
                "the device batch (" + std::to_string(a.instance_count) + " x " +
                    std::to_string(a.vertex_count) + ") and the reference batch (" +
                    std::to_string(b.instance_count) + " x " + std::to_string(b.vertex_count) +
                    ") do not match the model and the " + std::to_string(instances) + " instances");
  }
  const BodyFrame& root = model.rig().components.front().frame;
  AccuracyReport report;
  for (std::size_t i = 0; i < instances; ++i) {
    // World units per mesh unit, and the size of the coordinates the kernels handle.
    const double scale = placements ? double(placements[i].length) / root.length : 1.0;
    const double position_bound =
        kPositionBound *
        (placements ? glm::length(glm::dvec3(placements[i].position)) + double(placements[i].length)
                    : glm::length(root.origin) + root.length);
    const std::vector<double> row = row_of(model, parameters, i);
    for (std::size_t v = 0; v < model.vertex_count(); ++v) {
      detail::PathConditioning c;
      detail::deform_vertex(model, v, row.data(), normals, &c);
      const double stages = static_cast<double>(std::max<std::size_t>(c.stages, 1));

      const double position_error =
          glm::length(glm::dvec3(device.position(i, v)) - reference.position(i, v));
      const double bound =
          stages * position_bound + (c.near_limit ? kNearLimitBound * c.near_limit_z * scale : 0.0);
      report.max_position_error = std::max(report.max_position_error, position_error);
      report.max_position_ratio = std::max(report.max_position_ratio, position_error / bound);

      if (normals == NormalMode::kJacobian && (c.near_limit || c.near_fold)) {
        ++report.skipped_normals;
        continue;
      }
      double normal_error = glm::length(glm::dvec3(device.normal(i, v)) - reference.normal(i, v));
      if (a.tangents) {
        normal_error = std::max(
            normal_error, glm::length(glm::dvec3(device.tangent(i, v)) - reference.tangent(i, v)));
      }
      ++report.compared;
      report.max_normal_error = std::max(report.max_normal_error, normal_error);
      report.max_normal_ratio =
          std::max(report.max_normal_ratio,
                   normal_error / (c.near_limit ? kNearLimitBound : stages * kNormalBound));
    }
  }
  return report;
}

double mean_angle_to_face_normals(const Mesh& mesh) {
  Mesh from_faces = mesh;
  compute_vertex_normals(from_faces);
  double sum = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double cosine = glm::dot(glm::normalize(glm::dvec3(mesh.normals[v])),
                                   glm::normalize(glm::dvec3(from_faces.normals[v])));
    sum += std::acos(std::clamp(cosine, -1.0, 1.0));
  }
  return mesh.vertex_count() == 0 ? 0.0 : sum / static_cast<double>(mesh.vertex_count());
}

std::size_t count_folded_vertices(const RiggedMesh& model, const ParameterView& parameters,
                                  std::size_t instance) {
  if (instance >= parameters.instance_count) {
    throw Error(ErrorCode::kInvalidArgument, "instance",
                "instance = " + std::to_string(instance) + " is out of range (" +
                    std::to_string(parameters.instance_count) + " instances)");
  }
  const std::vector<double> row = row_of(model, parameters, instance);
  std::size_t folded = 0;
  for (std::size_t v = 0; v < model.vertex_count(); ++v) {
    detail::PathConditioning c;
    detail::deform_vertex(model, v, row.data(), NormalMode::kRotate, &c);
    folded += c.folded;
  }
  return folded;
}

}  // namespace finflex

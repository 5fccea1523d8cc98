#include "finflex/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "finflex/error.hpp"

namespace finflex {
namespace {

constexpr double kPositionBound = 4e-6;  // times (|origin| + s_x)
constexpr double kNormalBound = 2e-5;
constexpr double kNearLimit = 1e-3;  // 1 - (2mx)^2 below this: near the exact limit
constexpr double kNearLimitBound = 2e-3;
constexpr double kFoldMargin = 0.05;  // |1 - z k| below this: on a fold

// Spine curvature k at x (METHOD.md section 6): exact 2m / sqrt(1 - u^2); the series'
// (a u' - u a') / |df/dx|^3 with u = 2mx, a = 1 - u^2/2 - u^4/8.
double spine_curvature(double x, double m, BendMode mode) {
  const double u = std::clamp(2.0 * m * x, -1.0, 1.0);
  if (mode == BendMode::kExact) return 2.0 * m / std::max(std::sqrt((1.0 - u) * (1.0 + u)), 1e-6);
  const double a = 1.0 - u * u * (0.5 + 0.125 * u * u);
  const double g = std::sqrt(a * a + u * u);
  return 2.0 * m * (1.0 + u * u * (0.5 + 0.375 * u * u)) / (g * g * g);
}

}  // namespace

AccuracyReport compare_to_reference(const LocalMesh& local, const std::vector<float>& m,
                                    const BendSettings& settings,
                                    const DeformedBatch<float>& device,
                                    const DeformedBatch<double>& reference) {
  const BatchLayout& a = device.layout;
  const BatchLayout& b = reference.layout;
  if (a.vertex_count != local.vertex_count() || b.vertex_count != local.vertex_count() ||
      a.instance_count != m.size() || b.instance_count != m.size() || a.tangents != b.tangents) {
    throw Error(ErrorCode::kInvalidArgument, "device",
                "the device batch (" + std::to_string(a.instance_count) + " x " +
                    std::to_string(a.vertex_count) + ") and the reference batch (" +
                    std::to_string(b.instance_count) + " x " + std::to_string(b.vertex_count) +
                    ") do not match the mesh and the " + std::to_string(m.size()) + " parameters");
  }
  const BodyFrame& frame = local.frame;
  const double position_bound = kPositionBound * (glm::length(frame.origin) + frame.length);
  AccuracyReport report;
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t v = 0; v < local.vertex_count(); ++v) {
      const glm::dvec3& p = local.positions[v];
      const double u = 2.0 * m[i] * p.x;
      const bool near_limit = settings.mode == BendMode::kExact && 1.0 - u * u < kNearLimit;

      const double position_error =
          glm::length(glm::dvec3(device.position(i, v)) - reference.position(i, v));
      const double bound =
          position_bound + (near_limit ? kNearLimitBound * std::fabs(p.z) * frame.length : 0.0);
      report.max_position_error = std::max(report.max_position_error, position_error);
      report.max_position_ratio = std::max(report.max_position_ratio, position_error / bound);

      const bool ill_defined =
          settings.normals == NormalMode::kJacobian &&
          (near_limit ||
           std::fabs(1.0 - p.z * spine_curvature(p.x, m[i], settings.mode)) < kFoldMargin);
      if (ill_defined) {
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
      report.max_normal_ratio = std::max(
          report.max_normal_ratio, normal_error / (near_limit ? kNearLimitBound : kNormalBound));
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

std::size_t count_folded_vertices(const LocalMesh& local, double m, BendMode mode) {
  std::size_t folded = 0;
  for (const glm::dvec3& p : local.positions) {
    folded += p.z * spine_curvature(p.x, m, mode) >= 1.0;
  }
  return folded;
}

}  // namespace finflex

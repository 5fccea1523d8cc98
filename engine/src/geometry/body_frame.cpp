// BodyFrame (METHOD.md section 3, the paper's (1)-(2)) and the automatic frame of a
// fish: principal axes of its surface, then the signs and the lateral/dorsal choice by
// the heuristics documented in body_frame.hpp.
#include "finflex/body_frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "finflex/error.hpp"
#include "finflex/mesh.hpp"

namespace finflex {
namespace {

// | |axis| - 1 | and |axis_i . axis_j| allowed by BodyFrame::validate().
constexpr double kUnitTolerance = 1e-6;
// Relative eigenvalue gap below which two principal axes are taken as undefined.
constexpr double kAxisGapTolerance = 1e-3;
// |cos| of the angle between an override direction and the axis it orients below
// which the direction is taken as perpendicular (its sign says nothing).
constexpr double kDirectionTolerance = 1e-3;

std::string format_vec(const glm::dvec3& v) {
  std::ostringstream out;
  out.precision(9);
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

std::string format_double(double value) {
  std::ostringstream out;
  out.precision(9);
  out << value;
  return out.str();
}

bool is_finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// ---------------------------------------------------------------------------------
// Symmetric 3x3 eigen-decomposition by cyclic Jacobi rotations, in double.

struct SymmetricEigen {
  std::array<double, 3> values;       // descending
  std::array<glm::dvec3, 3> vectors;  // unit, vectors[i] belongs to values[i]
};

// Zeroes a[p][q] (p < q) by the rotation J = [[c, s], [-s, c]] in the (p, q) plane:
// a <- J^T a J, v <- v J (columns of v are the eigenvectors being accumulated).
void jacobi_rotate(double a[3][3], double v[3][3], int p, int q) {
  const double apq = a[p][q];
  if (apq == 0.0) return;
  // t = tan(phi) is the smaller root of t^2 + 2 theta t - 1 = 0.
  const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
  const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
  const double c = 1.0 / std::sqrt(t * t + 1.0);
  const double s = t * c;
  for (int k = 0; k < 3; ++k) {  // columns p, q
    const double akp = a[k][p];
    const double akq = a[k][q];
    a[k][p] = c * akp - s * akq;
    a[k][q] = s * akp + c * akq;
  }
  for (int k = 0; k < 3; ++k) {  // rows p, q
    const double apk = a[p][k];
    const double aqk = a[q][k];
    a[p][k] = c * apk - s * aqk;
    a[q][k] = s * apk + c * aqk;
  }
  a[p][q] = a[q][p] = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double vkp = v[k][p];
    const double vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

SymmetricEigen symmetric_eigen(const glm::dmat3& m) {
  double a[3][3];
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (m[c][r] + m[r][c]);  // glm: m[col][row]
  }
  double scale = 0.0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) scale += a[r][c] * a[r][c];
  }
  const double eps2 = 1e-36 * scale;  // (1e-18 relative)^2: converged to round-off
  for (int sweep = 0; sweep < 64; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off <= eps2) break;
    jacobi_rotate(a, v, 0, 1);
    jacobi_rotate(a, v, 0, 2);
    jacobi_rotate(a, v, 1, 2);
  }
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&a](int i, int j) { return a[i][i] > a[j][j]; });
  SymmetricEigen result{};
  for (int i = 0; i < 3; ++i) {
    const int k = order[static_cast<std::size_t>(i)];
    result.values[static_cast<std::size_t>(i)] = a[k][k];
    result.vectors[static_cast<std::size_t>(i)] =
        glm::normalize(glm::dvec3(v[0][k], v[1][k], v[2][k]));
  }
  return result;
}

// ---------------------------------------------------------------------------------
// Surface integrals over the triangles, exact for each flat triangle.
//
// With s_i = w . (vertex_i - mu) for a direction w, over a triangle of area A:
//   integral of (w.(p - mu))^2 = A/12 (sum s_i^2 + (sum s_i)^2)               (h2)
//   integral of (w.(p - mu))^3 = A/60 ((sum s_i)^3 + 3 (sum s_i)(sum s_i^2)
//                                      + 2 sum s_i^3)                           (h3)
// (from the integrals of barycentric monomials, 2A a! b! c! / (a + b + c + 2)!).

struct Triangle {
  glm::dvec3 a, b, c;
  glm::dvec3 doubled_normal;  // (b - a) x (c - a): length 2 A
  double area;
};

Triangle triangle_at(const Mesh& mesh, std::size_t t) {
  Triangle tri;
  tri.a = glm::dvec3(mesh.positions[mesh.indices[3 * t]]);
  tri.b = glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]);
  tri.c = glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]);
  tri.doubled_normal = glm::cross(tri.b - tri.a, tri.c - tri.a);
  tri.area = 0.5 * glm::length(tri.doubled_normal);
  return tri;
}

double second_moment_along(const Triangle& tri, const glm::dvec3& mu, const glm::dvec3& w) {
  const double s0 = glm::dot(w, tri.a - mu);
  const double s1 = glm::dot(w, tri.b - mu);
  const double s2 = glm::dot(w, tri.c - mu);
  const double sum = s0 + s1 + s2;
  return tri.area / 12.0 * (s0 * s0 + s1 * s1 + s2 * s2 + sum * sum);
}

double third_moment_along(const Triangle& tri, const glm::dvec3& mu, const glm::dvec3& w) {
  const double s0 = glm::dot(w, tri.a - mu);
  const double s1 = glm::dot(w, tri.b - mu);
  const double s2 = glm::dot(w, tri.c - mu);
  const double sum = s0 + s1 + s2;
  const double squares = s0 * s0 + s1 * s1 + s2 * s2;
  const double cubes = s0 * s0 * s0 + s1 * s1 * s1 + s2 * s2 * s2;
  return tri.area / 60.0 * (sum * sum * sum + 3.0 * sum * squares + 2.0 * cubes);
}

struct SurfaceMoments {
  double area = 0.0;
  glm::dvec3 centroid{0.0};
  glm::dmat3 covariance{0.0};  // per unit area, about the centroid
};

// mu = sum A_t c_t / sum A_t (c_t the triangle centroid); covariance from the exact
// per-triangle second moment A/12 (sum d_i d_i^T + (sum d_i)(sum d_i)^T), d_i = v_i - mu.
SurfaceMoments surface_moments(const Mesh& mesh) {
  SurfaceMoments m;
  glm::dvec3 weighted{0.0};
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = triangle_at(mesh, t);
    m.area += tri.area;
    weighted += tri.area * (tri.a + tri.b + tri.c) / 3.0;
  }
  if (!(m.area > 0.0)) {
    throw Error(ErrorCode::kInvalidMesh, "mesh",
                "mesh has zero surface area (" + std::to_string(mesh.triangle_count()) +
                    " triangles, none with area): its principal axes are undefined; give the "
                    "frame explicitly");
  }
  m.centroid = weighted / m.area;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = triangle_at(mesh, t);
    const glm::dvec3 d0 = tri.a - m.centroid;
    const glm::dvec3 d1 = tri.b - m.centroid;
    const glm::dvec3 d2 = tri.c - m.centroid;
    const glm::dvec3 sum = d0 + d1 + d2;
    m.covariance += (tri.area / 12.0) * (glm::outerProduct(d0, d0) + glm::outerProduct(d1, d1) +
                                         glm::outerProduct(d2, d2) + glm::outerProduct(sum, sum));
  }
  m.covariance /= m.area;
  return m;
}

// Area-weighted mean of (n . axis)^2 over the unit face normals n: how much the
// surface faces along `axis`. A fish's flanks and its flat median fins face sideways.
double facing_along(const Mesh& mesh, const glm::dvec3& axis) {
  double sum = 0.0;
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = triangle_at(mesh, t);
    if (!(tri.area > 0.0)) continue;
    const double cosine = glm::dot(tri.doubled_normal, axis) / (2.0 * tri.area);
    sum += tri.area * cosine * cosine;
    area += tri.area;
  }
  return sum / area;
}

// Area-weighted RMS of the coordinate along `lateral` (about mu) of the triangles
// whose centroid projects on e_x into [lo, hi]. Returns 0 when none does.
double lateral_rms(const Mesh& mesh, const glm::dvec3& mu, const glm::dvec3& ex,
                   const glm::dvec3& lateral, double lo, double hi) {
  double sum = 0.0;
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = triangle_at(mesh, t);
    const double x = glm::dot((tri.a + tri.b + tri.c) / 3.0 - mu, ex);
    if (x < lo || x > hi) continue;
    sum += second_moment_along(tri, mu, lateral);
    area += tri.area;
  }
  return area > 0.0 ? std::sqrt(sum / area) : 0.0;
}

double third_moment(const Mesh& mesh, const glm::dvec3& mu, const glm::dvec3& axis) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    sum += third_moment_along(triangle_at(mesh, t), mu, axis);
  }
  return sum;
}

// [min, max] of (p - mu) . axis over the vertices.
std::pair<double, double> vertex_extent(const Mesh& mesh, const glm::dvec3& mu,
                                        const glm::dvec3& axis) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    const double x = glm::dot(glm::dvec3(p) - mu, axis);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

// The unit form of an override direction, if given; kInvalidArgument naming `field`
// when it is zero or not finite.
std::optional<glm::dvec3> unit_direction(const std::optional<glm::dvec3>& direction,
                                         const char* field) {
  if (!direction) return std::nullopt;
  const double norm = glm::length(*direction);
  if (!is_finite(*direction) || !std::isfinite(norm) || !(norm > 0.0)) {
    throw Error(ErrorCode::kInvalidArgument, field,
                std::string(field) + " = " + format_vec(*direction) +
                    " must be a finite, non-zero direction");
  }
  return *direction / norm;
}

// The sign (+1 or -1) of unit . axis; kInvalidArgument naming `field` (whose given
// value is `raw`) when the direction is perpendicular to the axis within
// kDirectionTolerance.
double override_sign(const glm::dvec3& unit, const glm::dvec3& axis, const glm::dvec3& raw,
                     const char* field, const char* axis_name) {
  const double cosine = glm::dot(unit, axis);
  if (std::abs(cosine) < kDirectionTolerance) {
    throw Error(ErrorCode::kInvalidArgument, field,
                std::string(field) + " = " + format_vec(raw) + " is perpendicular to the found " +
                    axis_name + " " + format_vec(axis) + " (cos = " + format_double(cosine) +
                    "): its sign is undefined");
  }
  return cosine > 0.0 ? 1.0 : -1.0;
}

// The dorsal axis e_y (unit, perpendicular to ex, sign not yet fixed) among the two
// minor principal axes u, v (eigenvalues lu >= lv). `dorsal`: the unit form of
// options.dorsal_direction, if given.
glm::dvec3 choose_dorsal_axis(const Mesh& mesh, const glm::dvec3& ex, const glm::dvec3& u,
                              const glm::dvec3& v, double lu, double lv,
                              const std::optional<glm::dvec3>& dorsal,
                              const FrameOptions& options) {
  const bool round_cross_section = lu - lv <= kAxisGapTolerance * lu;
  if (dorsal && round_cross_section) {
    // u, v are arbitrary: the part of `dorsal` across the spine defines e_y.
    const glm::dvec3 across = *dorsal - glm::dot(*dorsal, ex) * ex;
    const double norm = glm::length(across);
    if (norm < kDirectionTolerance) {
      throw Error(ErrorCode::kInvalidArgument, "options.dorsal_direction",
                  "options.dorsal_direction = " + format_vec(*options.dorsal_direction) +
                      " is parallel to the spine " + format_vec(ex) +
                      ": it cannot orient the dorsal axis");
    }
    return across / norm;
  }
  if (dorsal) {  // the user's "up": the principal axis closer to it is dorsal
    return std::abs(glm::dot(*dorsal, u)) >= std::abs(glm::dot(*dorsal, v)) ? u : v;
  }
  if (round_cross_section) {
    throw Error(ErrorCode::kInvalidMesh, "mesh",
                "mesh cross-section is round (second moments " + format_double(lu) + " and " +
                    format_double(lv) +
                    " across the spine): the dorsal axis is undefined; give "
                    "FrameOptions::dorsal_direction");
  }
  // Lateral = the principal axis the surface faces most; the other one is dorsal.
  return facing_along(mesh, u) >= facing_along(mesh, v) ? v : u;
}

}  // namespace

// ---------------------------------------------------------------------------------
// BodyFrame: p_local = R_b (p - origin) / length, R_b's rows axis_x, axis_y, axis_z.

glm::dvec3 BodyFrame::point_to_local(const glm::dvec3& p) const {
  return vector_to_local(p - origin) / length;
}

glm::dvec3 BodyFrame::point_to_mesh(const glm::dvec3& p) const {
  return origin + length * vector_to_mesh(p);
}

glm::dvec3 BodyFrame::vector_to_local(const glm::dvec3& v) const {
  return {glm::dot(axis_x, v), glm::dot(axis_y, v), glm::dot(axis_z, v)};
}

glm::dvec3 BodyFrame::vector_to_mesh(const glm::dvec3& v) const {
  return v.x * axis_x + v.y * axis_y + v.z * axis_z;  // R_b^T v
}

void BodyFrame::validate() const {
  if (!is_finite(origin)) {
    throw Error(ErrorCode::kInvalidArgument, "origin",
                "origin = " + format_vec(origin) + " is not finite");
  }
  const std::array<std::pair<const char*, const glm::dvec3*>, 3> axes = {
      {{"axis_x", &axis_x}, {"axis_y", &axis_y}, {"axis_z", &axis_z}}};
  for (const auto& [name, axis] : axes) {
    const std::string field = name;
    if (!is_finite(*axis)) {
      throw Error(ErrorCode::kInvalidArgument, field,
                  field + " = " + format_vec(*axis) + " is not finite");
    }
    const double norm = glm::length(*axis);
    if (std::abs(norm - 1.0) > kUnitTolerance) {
      throw Error(
          ErrorCode::kInvalidArgument, field,
          field + " = " + format_vec(*axis) + " is not unit (length " + format_double(norm) + ")");
    }
  }
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i + 1; j < 3; ++j) {
      const double cosine = glm::dot(*axes[i].second, *axes[j].second);
      if (std::abs(cosine) > kUnitTolerance) {
        const std::string field = axes[j].first;
        throw Error(ErrorCode::kInvalidArgument, field,
                    field + " = " + format_vec(*axes[j].second) + " is not orthogonal to " +
                        axes[i].first + " = " + format_vec(*axes[i].second) + " (dot " +
                        format_double(cosine) + ")");
      }
    }
  }
  const double handedness = glm::dot(glm::cross(axis_x, axis_y), axis_z);
  if (!(handedness > 0.0)) {
    throw Error(ErrorCode::kInvalidArgument, "axis_z",
                "axis_z = " + format_vec(axis_z) +
                    " makes a left-handed frame (axis_x x axis_y = " +
                    format_vec(glm::cross(axis_x, axis_y)) + ")");
  }
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw Error(ErrorCode::kInvalidArgument, "length",
                "length = " + format_double(length) + " must be finite and > 0");
  }
}

// ---------------------------------------------------------------------------------

BodyFrame find_body_frame(const Mesh& mesh, const FrameOptions& options) {
  validate_mesh(mesh);
  const std::optional<glm::dvec3> head =
      unit_direction(options.head_direction, "options.head_direction");
  const std::optional<glm::dvec3> dorsal =
      unit_direction(options.dorsal_direction, "options.dorsal_direction");
  if (options.pivot && !is_finite(*options.pivot)) {
    throw Error(ErrorCode::kInvalidArgument, "options.pivot",
                "options.pivot = " + format_vec(*options.pivot) + " is not finite");
  }

  // 1. Spine: the principal axis of largest second moment.
  const SurfaceMoments moments = surface_moments(mesh);
  const glm::dvec3 mu = moments.centroid;
  const SymmetricEigen eigen = symmetric_eigen(moments.covariance);
  const double l0 = eigen.values[0];
  if (!(l0 - eigen.values[1] > kAxisGapTolerance * l0)) {
    throw Error(ErrorCode::kInvalidMesh, "mesh",
                "mesh has no dominant axis (largest second moments " + format_double(l0) + " and " +
                    format_double(eigen.values[1]) +
                    " within a relative 1e-3): the spine is undefined; give the frame "
                    "explicitly (e.g. BodyFrame) instead of find_body_frame");
  }
  glm::dvec3 ex = eigen.vectors[0];

  // 2. Dorsal and lateral axes (signs still open).
  glm::dvec3 ey = choose_dorsal_axis(mesh, ex, eigen.vectors[1], eigen.vectors[2], eigen.values[1],
                                     eigen.values[2], dorsal, options);
  const glm::dvec3 lateral = glm::normalize(glm::cross(ex, ey));

  // 3. Head: the end whose outer third (by vertex extent on e_x) is thicker laterally.
  const auto [lo, hi] = vertex_extent(mesh, mu, ex);
  const double third = (hi - lo) / 3.0;
  if (head) {
    ex *= override_sign(*head, ex, *options.head_direction, "options.head_direction", "spine axis");
  } else if (lateral_rms(mesh, mu, ex, lateral, lo, lo + third) >
             lateral_rms(mesh, mu, ex, lateral, hi - third, hi)) {
    ex = -ex;
  }

  // 4. Dorsal side: the positive third moment along e_y.
  if (dorsal) {
    ey *= override_sign(*dorsal, ey, *options.dorsal_direction, "options.dorsal_direction",
                        "dorsal axis");
  } else if (third_moment(mesh, mu, ey) < 0.0) {
    ey = -ey;
  }

  // 5.-6. Pivot and length.
  BodyFrame frame;
  frame.origin = options.pivot ? *options.pivot : mu;
  frame.axis_x = ex;
  frame.axis_y = ey;
  frame.axis_z = glm::cross(ex, ey);
  frame.length = hi - lo;
  if (!(frame.length > 0.0)) {
    throw Error(ErrorCode::kInvalidMesh, "mesh", "mesh has zero extent along its spine");
  }
  return frame;
}

}  // namespace finflex

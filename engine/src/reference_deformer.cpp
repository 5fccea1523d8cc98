#include "finflex/reference_deformer.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

namespace finflex {
namespace {

// The floor on sqrt(1 - 4m^2x^2) where the exact bend's curvature 2m / sqrt(...) is
// infinite (the spine's end at the range limit); the OpenCL kernels use the same floor.
constexpr double kMinSpineCosine = 1e-6;

// The secant surface along the spine at one x: f(x, 0), df/dx, the unit normal n and
// dn/dx (for the Jacobian). y passes through unchanged: df/dy = e_y (16).
struct SpineSample {
  glm::dvec3 f;
  glm::dvec3 df_dx;
  glm::dvec3 n;
  glm::dvec3 dn_dx;
};

// Paper: f = (x (1 - 2/3 m^2x^2 - 2/5 m^4x^4), 0, m x^2) (16); df/dx = (a, 0, 2mx) with
// a = 1 - 2m^2x^2 - 2m^4x^4; n = (-2mx, 0, a) / |.| (17).
SpineSample paper_spine(double x, double m) {
  const double mx2 = m * m * x * x;
  const double a = 1.0 - 2.0 * mx2 - 2.0 * mx2 * mx2;
  const double b = 2.0 * m * x;
  const double da = -4.0 * m * m * x - 8.0 * m * m * m * m * x * x * x;
  const double db = 2.0 * m;
  const double g = std::sqrt(a * a + b * b);
  const double dg = (a * da + b * db) / g;
  SpineSample s;
  s.f = {x * (1.0 - 2.0 / 3.0 * mx2 - 2.0 / 5.0 * mx2 * mx2), 0.0, m * x * x};
  s.df_dx = {a, 0.0, b};
  s.n = glm::dvec3(-b, 0.0, a) / g;
  s.dn_dx = (glm::dvec3(-db, 0.0, da) * g - glm::dvec3(-b, 0.0, a) * dg) / (g * g);
  return s;
}

// Exact: dx'/dx = sqrt(1 - 4m^2x^2) (13) integrated in closed form,
// x' = x sqrt(1 - 4m^2x^2) / 2 + asin(2mx) / (4m) (-> x as m -> 0);
// unit tangent (c, 0, 2mx), n = (-2mx, 0, c), c = sqrt(1 - 4m^2x^2).
SpineSample exact_spine(double x, double m) {
  const double u = std::clamp(2.0 * m * x, -1.0, 1.0);
  const double c = std::sqrt((1.0 - u) * (1.0 + u));
  const double asin_u_over_u = std::fabs(u) < 1e-4 ? 1.0 + u * u / 6.0 : std::asin(u) / u;
  const double dc_dx = -2.0 * m * u / std::max(c, kMinSpineCosine);
  SpineSample s;
  s.f = {0.5 * x * (c + asin_u_over_u), 0.0, m * x * x};
  s.df_dx = {c, 0.0, u};
  s.n = {-u, 0.0, c};
  s.dn_dx = {-2.0 * m, 0.0, dc_dx};
  return s;
}

// Rodrigues rotation taking e_z to the unit vector n (8): about k = e_z x n by the
// angle between them (the paper's e_r = n x e_z, turned clockwise). R = I when n = e_z.
glm::dmat3 rotation_from_ez(const glm::dvec3& n) {
  const glm::dvec3 r = glm::cross(glm::dvec3(0.0, 0.0, 1.0), n);
  const double sin_theta = glm::length(r);
  if (sin_theta < 1e-300) return glm::dmat3(1.0);
  const glm::dvec3 k = r / sin_theta;
  const double cos_theta = n.z;
  const glm::dmat3 kx(0.0, k.z, -k.y, -k.z, 0.0, k.x, k.y, -k.x, 0.0);  // columns of [k]x
  return glm::dmat3(1.0) + sin_theta * kx + (1.0 - cos_theta) * kx * kx;
}

}  // namespace

LocalVertex bend_local_vertex(const LocalVertex& rest, double m, const BendSettings& settings) {
  const glm::dvec3& p = rest.position;
  const SpineSample s =
      settings.mode == BendMode::kExact ? exact_spine(p.x, m) : paper_spine(p.x, m);
  LocalVertex out;
  // (7): p' = f(x, y, 0) + z n.
  out.position = s.f + glm::dvec3(0.0, p.y, 0.0) + p.z * s.n;
  if (settings.normals == NormalMode::kRotate) {
    const glm::dmat3 r = rotation_from_ez(s.n);  // (8)
    out.normal = glm::normalize(r * rest.normal);
    out.tangent = r * rest.tangent;
  } else {
    // J = [df/dx + z dn/dx, e_y, n]; normals by cof(J) = det(J) J^-T, which is what the
    // cross product of deformed triangle edges gives, fold-over included.
    const glm::dmat3 j(s.df_dx + p.z * s.dn_dx, glm::dvec3(0.0, 1.0, 0.0), s.n);
    const glm::dmat3 cofactor = glm::determinant(j) * glm::inverseTranspose(j);
    out.normal = glm::normalize(cofactor * rest.normal);
    out.tangent = j * rest.tangent;
  }
  if (glm::dot(out.tangent, out.tangent) > 0.0) out.tangent = glm::normalize(out.tangent);
  return out;
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

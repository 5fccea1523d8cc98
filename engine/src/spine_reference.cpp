#include "spine_reference.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

namespace finflex::detail {
namespace {

// The floor on sqrt(1 - 4m^2x^2) where the exact bend's curvature 2m / sqrt(...) is
// infinite (the spine's end at the range limit); the OpenCL kernels use the same floor.
constexpr double kMinSpineCosine = 1e-6;

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

SpineSample hinge_spine(double x, double angle, double width) {
  // theta(x) = angle * clamp(x / width, 0, 1); X' = cos(theta), Z' = sin(theta):
  // for 0 < x < width, X = (width/angle) sin(theta), Z = (width/angle) (1 - cos(theta));
  // past the ramp the part turns rigidly by `angle`.
  const double ramp = width > 0.0 ? std::clamp(x, 0.0, width) : 0.0;
  const double beyond = std::max(x - width, 0.0);
  const double fraction = width > 0.0 ? ramp / width : (x > 0.0 ? 1.0 : 0.0);
  const double theta = angle * fraction;
  const double sin_over_theta = std::fabs(theta) < 1e-8 ? 1.0 : std::sin(theta) / theta;
  const double versine_over_theta =
      std::fabs(theta) < 1e-8 ? 0.5 * theta : (1.0 - std::cos(theta)) / theta;
  const glm::dvec3 t(std::cos(theta), 0.0, std::sin(theta));
  const double curvature = (width > 0.0 && x > 0.0 && x < width) ? angle / width : 0.0;
  SpineSample s;
  s.f = {std::min(x, 0.0) + ramp * sin_over_theta + beyond * t.x, 0.0,
         ramp * versine_over_theta + beyond * t.z};
  s.df_dx = t;
  s.n = {-t.z, 0.0, t.x};
  s.dn_dx = -curvature * t;  // d/dx (-sin, 0, cos) = -theta'(x) (cos, 0, sin)
  return s;
}

LocalVertex apply_spine(const LocalVertex& rest, const SpineSample& s, NormalMode normals) {
  const glm::dvec3& p = rest.position;
  LocalVertex out;
  // (7): p' = f(x, y, 0) + z n.
  out.position = s.f + glm::dvec3(0.0, p.y, 0.0) + p.z * s.n;
  if (normals == NormalMode::kRotate) {
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

}  // namespace finflex::detail

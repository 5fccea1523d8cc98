#include "reference/secant_surface.hpp"

#include <glm/gtc/matrix_inverse.hpp>

namespace finflex::detail {
namespace {

// Rodrigues rotation taking e_z to the unit vector n (8): about k = e_z x n by the
// angle between them (the paper's e_r = n x e_z, turned clockwise). R = I when n = e_z.
// Not the matrix printed as (9): that one is its transpose (METHOD.md section 4).
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

Vertex apply_secant(const Vertex& rest, const SecantSample& s, NormalMode normals) {
  const glm::dvec3& p = rest.position;
  Vertex out;
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

namespace finflex {

LocalVertex apply_stage(const DeformerType& deformer, const StageOptions& options,
                        const double* values, const LocalVertex& rest, NormalMode normals,
                        const StageGeometry& geometry) {
  return detail::apply_secant(rest, deformer.secant(rest.position.x, values, options, geometry),
                              normals);
}

}  // namespace finflex

#include "render/refraction.hpp"

#include <cmath>

namespace finflex::render {

std::optional<glm::dvec3> refraction_point(const Scene& scene, const glm::dvec3& eye,
                                           const glm::dvec3& point) {
  const double surface = scene.tank.water_depth;
  if (!scene.view_refraction || eye.y <= surface || point.y >= surface) return std::nullopt;
  const double n = scene.water.refractive_index;
  const double h = eye.y - surface;
  const double d = surface - point.y;
  const glm::dvec2 across(point.x - eye.x, point.z - eye.z);
  const double r = glm::length(across);
  double x = 0.0;  // from the eye's foot towards the point, on [0, r]
  if (r > 0.0) {
    // f(x) = x b - n (r - x) a rises from -n r h to r d: bisection to the last bits.
    double low = 0.0, high = r;
    for (int i = 0; i < 200 && high - low > 1e-15 * (1.0 + r); ++i) {
      x = 0.5 * (low + high);
      const double a = std::hypot(x, h), b = std::hypot(r - x, d);
      (x * b - n * (r - x) * a < 0.0 ? low : high) = x;
    }
    x = 0.5 * (low + high);
  }
  const glm::dvec2 towards = r > 0.0 ? across * (x / r) : glm::dvec2(0.0);
  return glm::dvec3(eye.x + towards.x, surface, eye.z + towards.y);
}

glm::dvec3 apparent_point(const Scene& scene, const Camera& camera, const glm::dvec3& point) {
  const glm::dvec3 eye(camera.position);
  const std::optional<glm::dvec3> q = refraction_point(scene, eye, point);
  if (!q) return point;
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
  const double t = glm::dot(point - eye, forward) / glm::dot(*q - eye, forward);
  return eye + t * (*q - eye);
}

}  // namespace finflex::render

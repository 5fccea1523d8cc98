#include "render/refraction.hpp"

#include <cmath>

namespace finflex::render {
namespace {

// The lateral run per unit of depth of a ray of sine s (in air) in a medium of index m.
double run(double s, double m) {
  const double q = s / m;
  return q / std::sqrt(1.0 - q * q);
}

}  // namespace

std::optional<RefractedRay> refracted_ray(const Scene& scene, const Camera& camera,
                                          const glm::dvec3& point) {
  const glm::dvec3 eye(camera.position);
  // The interface: its normal towards the camera, the camera's distance h from its near
  // face, and the window between its faces (none at the surface).
  glm::dvec3 normal(0.0, 1.0, 0.0);
  double h = 0.0, t = 0.0, window = 1.0;
  switch (scene.view_refraction) {
    case ViewRefraction::kNone:
      return std::nullopt;
    case ViewRefraction::kSurface:
      h = eye.y - double(scene.tank.water_depth);
      break;
    case ViewRefraction::kPort:
      normal = -glm::normalize(glm::dvec3(camera.target) - eye);
      h = scene.port.distance;
      t = scene.port.thickness;
      window = scene.port.refractive_index;
      break;
  }
  const double n = scene.water.refractive_index;
  const glm::dvec3 v = point - eye;
  const double along = -glm::dot(v, normal);
  const double d = along - h - t;
  if (h <= 0.0 || d <= 0.0) return std::nullopt;
  const glm::dvec3 lateral = v + along * normal;
  const double r = glm::length(lateral);
  double x = 0.0, s = 0.0;  // on [0, r]: the run in air rises from -r to >= 0 at r
  if (r > 0.0) {
    double low = 0.0, high = r;
    for (int i = 0; i < 200 && high - low > 1e-15 * (1.0 + r); ++i) {
      x = 0.5 * (low + high);
      s = x / std::hypot(x, h);
      (x + t * run(s, window) + d * run(s, n) < r ? low : high) = x;
    }
    x = 0.5 * (low + high);
    s = x / std::hypot(x, h);
  }
  const glm::dvec3 side = r > 0.0 ? lateral / r : glm::dvec3(0.0);
  RefractedRay ray;
  ray.entry = eye - h * normal + x * side;
  ray.exit = ray.entry - t * normal + t * run(s, window) * side;
  return ray;
}

glm::dvec3 apparent_point(const Scene& scene, const Camera& camera, const glm::dvec3& point) {
  const std::optional<RefractedRay> ray = refracted_ray(scene, camera, point);
  if (!ray) return point;
  const glm::dvec3 eye(camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
  const double k = glm::dot(point - eye, forward) / glm::dot(ray->entry - eye, forward);
  return eye + k * (ray->entry - eye);
}

}  // namespace finflex::render

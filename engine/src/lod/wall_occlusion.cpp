#include "finflex/wall_occlusion.hpp"

#include <algorithm>
#include <cmath>

#include "finflex/error.hpp"

namespace finflex {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void invalid(const std::string& field, const std::string& why) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + why);
}

// The distance along a horizontal direction at angle phi from the direction to the
// axis (its cosine and sine), from an eye at distance m from the axis, to where it leaves
// the circle of radius r (the square root's argument held at 0 where it misses).
double exit_distance(double m, double cos_phi, double sin_phi, double r) {
  const double across = m * sin_phi;
  return m * cos_phi + std::sqrt(std::max(0.0, r * r - across * across));
}

}  // namespace

double WallOccluder::inner_radius() const {
  return sides == 0 ? radius : radius * std::cos(kPi / double(sides));
}

void WallOccluder::validate(const std::string& field) const {
  if (!(std::isfinite(base.x) && std::isfinite(base.y) && std::isfinite(base.z))) {
    invalid(field + ".base", "not finite");
  }
  if (!(std::isfinite(radius) && radius > 0.0)) {
    invalid(field + ".radius", std::to_string(radius) + " is not > 0");
  }
  if (!(std::isfinite(height) && height > 0.0)) {
    invalid(field + ".height", std::to_string(height) + " is not > 0");
  }
  if (sides < 0 || sides == 1 || sides == 2) {
    invalid(field + ".sides", std::to_string(sides) + " is not 0 (a cylinder) or 3 or more");
  }
}

bool wall_hides_sphere(const glm::dvec3& eye, const glm::dvec3& centre, double radius,
                       const WallOccluder& wall) {
  const double outer = wall.radius;
  const double inner = wall.inner_radius();
  const glm::dvec2 to_axis(wall.base.x - eye.x, wall.base.z - eye.z);
  const glm::dvec2 to_sphere(centre.x - eye.x, centre.z - eye.z);
  const double d = glm::length(to_sphere);
  if (!(d > radius)) return false;
  const double m = glm::length(to_axis);
  // The axis along and across the direction to the sphere's centre (m cos beta, m sin
  // beta). Two conditions the full test implies, cheap, first: from outside, that
  // direction meets the inscribed circle; the outer circle's exit along it (no nearer
  // than the wedge's farthest) comes before the sphere.
  const glm::dvec2 u = to_sphere / d;
  const double along = glm::dot(u, to_axis);
  const double across = std::abs(u.x * to_axis.y - u.y * to_axis.x);
  const bool outside = m >= inner;
  if (outside && (along <= 0.0 || across >= inner)) return false;
  if (!(along + std::sqrt(std::max(0.0, outer * outer - across * across)) < d - radius)) {
    return false;
  }
  // The wedge's half-angle alpha (sin = r / d) about beta: its widest angle from the
  // axis's direction beta + alpha (at most pi, where the exit is nearest), its narrowest
  // max(beta - alpha, 0), by their cosines and sines.
  const double sin_a = radius / d, cos_a = std::sqrt(1.0 - sin_a * sin_a);
  const double cos_b = m > 0.0 ? along / m : 1.0, sin_b = m > 0.0 ? across / m : 0.0;
  double cos_wide = cos_b * cos_a - sin_b * sin_a, sin_wide = sin_b * cos_a + cos_b * sin_a;
  if (sin_wide < 0.0 || (sin_wide == 0.0 && cos_wide < 0.0)) {
    cos_wide = -1.0;
    sin_wide = 0.0;
  }
  double cos_narrow = cos_b * cos_a + sin_b * sin_a, sin_narrow = sin_b * cos_a - cos_b * sin_a;
  if (sin_narrow < 0.0) {
    cos_narrow = 1.0;
    sin_narrow = 0.0;
  }
  if (outside && !(cos_wide > 0.0 && m * sin_wide < inner)) return false;
  const double nearest_exit = exit_distance(m, cos_wide, sin_wide, inner);
  const double farthest_exit = exit_distance(m, cos_narrow, sin_narrow, outer);
  if (!(farthest_exit < d - radius)) return false;
  const double eye_height = eye.y - wall.base.y;
  const double centre_height = centre.y - wall.base.y;
  for (const double point_height : {centre_height - radius, centre_height + radius}) {
    for (const double share : {nearest_exit / (d + radius), farthest_exit / (d - radius)}) {
      const double height = eye_height + (point_height - eye_height) * share;
      if (!(height >= 0.0 && height <= wall.height)) return false;
    }
  }
  return true;
}

}  // namespace finflex

// The hinge (METHOD.md section 6: the general inextensible spine, its angle ramping
// linearly): a fin folding about its base. In the stage's frame the spine's angle
// theta(x) ramps from 0 at x = 0 to `angle` at x = width (a step at 0 when width = 0);
// x < 0 is untouched, the ramp bends into a circular arc, the part beyond turns
// rigidly. One value per instance, the angle, |angle| <= pi. Option "width" >= 0, in
// the frame's normalised lengths. OpenCL: kernels/deformers/hinge.cl.
#include <algorithm>
#include <cmath>
#include <limits>

#include "finflex/deformer_type.hpp"

namespace finflex {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kWidth = 0;  // option index of "width"

// theta(x) = angle * clamp(x / width, 0, 1); X' = cos(theta), Z' = sin(theta):
// for 0 < x < width, X = (width/angle) sin(theta), Z = (width/angle) (1 - cos(theta));
// past the ramp the part turns rigidly by `angle`. k = angle / width in the ramp.
SecantSample hinge_secant(double x, double angle, double width) {
  const double ramp = width > 0.0 ? std::clamp(x, 0.0, width) : 0.0;
  const double beyond = std::max(x - width, 0.0);
  const double fraction = width > 0.0 ? ramp / width : (x > 0.0 ? 1.0 : 0.0);
  const double theta = angle * fraction;
  const double sin_over_theta = std::fabs(theta) < 1e-8 ? 1.0 : std::sin(theta) / theta;
  const double versine_over_theta =
      std::fabs(theta) < 1e-8 ? 0.5 * theta : (1.0 - std::cos(theta)) / theta;
  const glm::dvec3 t(std::cos(theta), 0.0, std::sin(theta));
  const double curvature = (width > 0.0 && x > 0.0 && x < width) ? angle / width : 0.0;
  SecantSample s;
  s.f = {std::min(x, 0.0) + ramp * sin_over_theta + beyond * t.x, 0.0,
         ramp * versine_over_theta + beyond * t.z};
  s.df_dx = t;
  s.n = {-t.z, 0.0, t.x};
  s.dn_dx = -curvature * t;  // d/dx (-sin, 0, cos) = -theta'(x) (cos, 0, sin)
  s.curvature = curvature;
  return s;
}

// The description, built on first use rather than a global: the registry may be read
// while other files are statically initialised.
const DeformerType& hinge_type() {
  static const DeformerType type = {
      "hinge",
      "a fin folding about its base: the angle ramps from 0 to `angle` over x in [0, width]",
      "the fold angle in radians; |angle| <= pi",
      {{"width",
        {},
        0.0,
        std::numeric_limits<double>::infinity(),
        false,
        0.0,
        "the ramp's width in x (the frame's lengths), >= 0"}},
      [](const StageOptions&) -> std::size_t { return 1; },
      [](const StageOptions&, const StageGeometry&) { return kPi; },
      [](double x, const double* values, const StageOptions& options, const StageGeometry&) {
        return hinge_secant(x, values[0], options[kWidth]);
      },
      "deformers/hinge.cl",
      [](const StageOptions&) { return "hinge_stage"; },
      [](const StageOptions& options, const StageGeometry&) {
        // The kernel's hinge_sample reads width and 1 / width (0 for width 0).
        const double width = options[kWidth];
        return StageConstants{width, width > 0.0 ? 1.0 / width : 0.0, 0.0, 0.0};
      },
  };
  return type;
}

}  // namespace

namespace deformers {
const DeformerType& hinge() { return hinge_type(); }
}  // namespace deformers

}  // namespace finflex

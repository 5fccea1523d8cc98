// The general inextensible spine (METHOD.md section 6): per instance a table of
// tangent angles theta_k at `samples` points evenly spaced over the stage's extent in
// x (its first sample at the vertices' lowest x, its last at their highest), theta
// linear in between and constant beyond. X(x) = integral_0^x cos theta and
// Z(x) = integral_0^x sin theta in closed form per segment, so the spine keeps its
// arc length exactly at any angle; x = 0 stays fixed. The paper's bend is the case
// theta = asin(2 m x). Values: the angles in radians, |theta| <= pi. A table whose
// curvature would fold the surface through itself (z k >= 1 for a vertex of the
// stage, METHOD.md section 6) is refused, or with clamping bent less.
// OpenCL: kernels/deformers/spine.cl.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "finflex/deformer_type.hpp"
#include "finflex/error.hpp"

namespace finflex {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kSamples = 0;  // option index of "samples"
// Clamping keeps z k at most this: a margin below the fold.
constexpr double kClampedFold = 0.95;

std::size_t samples_of(const StageOptions& options) {
  return static_cast<std::size_t>(options[kSamples]);
}

// The table's spacing: the stage's extent over its segments (1 without extent).
double spacing(const StageOptions& options, const StageGeometry& geometry) {
  const double extent = geometry.x_highest - geometry.x_lowest;
  return extent > 0.0 ? extent / double(samples_of(options) - 1) : 1.0;
}

double sinc(double u) { return std::fabs(u) < 1e-8 ? 1.0 - u * u / 6.0 : std::sin(u) / u; }

// The spine from the first sample to x: (integral cos, integral sin), theta at x, and
// theta'(x).
struct Running {
  double x = 0.0, z = 0.0, theta = 0.0, curvature = 0.0;
};

Running integrate_to(double x, const double* theta, std::size_t samples, double x_first, double h) {
  Running r;
  const double position = (x - x_first) / h;
  const std::size_t last_segment = samples - 2;
  std::size_t j = 0;
  // Whole segments before x's, in closed form.
  while (j < last_segment && position >= double(j + 1)) {
    const double half = 0.5 * (theta[j + 1] - theta[j]);
    r.x += h * std::cos(theta[j] + half) * sinc(half);
    r.z += h * std::sin(theta[j] + half) * sinc(half);
    ++j;
  }
  const double d = (position - double(j)) * h;
  const double inside = std::clamp(d, 0.0, h);
  const double beyond = d - inside;
  const double slope = (theta[j + 1] - theta[j]) / h;
  const double half = 0.5 * slope * inside;
  r.theta = theta[j] + 2.0 * half;
  r.x += inside * std::cos(theta[j] + half) * sinc(half) + beyond * std::cos(r.theta);
  r.z += inside * std::sin(theta[j] + half) * sinc(half) + beyond * std::sin(r.theta);
  r.curvature = beyond == 0.0 ? slope : 0.0;
  return r;
}

SecantSample spine_secant(double x, const double* theta, const StageOptions& options,
                          const StageGeometry& geometry) {
  const std::size_t samples = samples_of(options);
  const double h = spacing(options, geometry);
  const Running at = integrate_to(x, theta, samples, geometry.x_lowest, h);
  const Running origin = integrate_to(0.0, theta, samples, geometry.x_lowest, h);
  const glm::dvec3 t(std::cos(at.theta), 0.0, std::sin(at.theta));
  SecantSample s;
  s.f = {at.x - origin.x, 0.0, at.z - origin.z};
  s.df_dx = t;
  s.n = {-t.z, 0.0, t.x};
  s.dn_dx = -at.curvature * t;  // d/dx (-sin, 0, cos) = -theta'(x) (cos, 0, sin)
  s.curvature = at.curvature;
  return s;
}

// Per segment, the largest z on each side among the vertices whose x falls in it
// (those beyond the ends in the end segments): [z+ of every segment, then |z-|].
std::vector<double> measure_spine(const StageOptions& options,
                                  const std::vector<glm::dvec3>& local) {
  StageGeometry geometry;
  if (!local.empty()) geometry.x_lowest = geometry.x_highest = local.front().x;
  for (const glm::dvec3& p : local) {
    geometry.x_lowest = std::min(geometry.x_lowest, p.x);
    geometry.x_highest = std::max(geometry.x_highest, p.x);
  }
  if (!(geometry.x_highest > geometry.x_lowest)) {
    throw Error(ErrorCode::kInvalidArgument, "spine",
                "a spine stage's vertices have no extent along its x");
  }
  const std::size_t segments = samples_of(options) - 1;
  const double h = spacing(options, geometry);
  std::vector<double> extents(2 * segments, 0.0);
  for (const glm::dvec3& p : local) {
    const double position = std::floor((p.x - geometry.x_lowest) / h);
    const std::size_t j = static_cast<std::size_t>(std::clamp(position, 0.0, double(segments - 1)));
    if (p.z > 0.0) extents[j] = std::max(extents[j], p.z);
    if (p.z < 0.0) extents[segments + j] = std::max(extents[segments + j], -p.z);
  }
  return extents;
}

// Fold-over (METHOD.md section 6): a vertex at z folds where z k >= 1, k = the
// segment's curvature (theta_{j+1} - theta_j) / h.
std::string check_spine(float* theta, const StageOptions& options, const StageGeometry& geometry,
                        bool clamp) {
  const std::size_t segments = samples_of(options) - 1;
  const double h = spacing(options, geometry);
  const std::vector<double>& extents = geometry.measurements;
  // The common case first, in one branch-free pass: no segment near a fold (z k below
  // 1 - 1e-9, so rounding cannot hide one the exact test below would find).
  const double inverse_h = 1.0 / h;
  int near_fold = 0;
  for (std::size_t j = 0; j < segments; ++j) {
    const double turn = double(theta[j + 1]) - double(theta[j]);
    const double z = turn > 0.0 ? extents[j] : extents[segments + j];
    near_fold |= std::fabs(turn) * z * inverse_h >= 1.0 - 1e-9;
  }
  if (!near_fold) return "";
  for (std::size_t j = 0; j < segments; ++j) {
    const double k = (double(theta[j + 1]) - double(theta[j])) / h;
    const double z = k > 0.0 ? extents[j] : extents[segments + j];
    if (std::fabs(k) * z < 1.0) continue;
    if (clamp) {
      // Bend this segment less, turning everything after it with it.
      const double limited = std::copysign(kClampedFold / z, k);
      const float shift = static_cast<float>((limited - k) * h);
      for (std::size_t after = j + 1; after <= segments; ++after) theta[after] += shift;
      continue;
    }
    std::ostringstream message;
    message.precision(4);
    message << "segment " << j << " (x in [" << geometry.x_lowest + double(j) * h << ", "
            << geometry.x_lowest + double(j + 1) * h << "]) has curvature " << k
            << ", which folds the surface through itself: a vertex " << z
            << " off the spine lies beyond its radius of curvature " << 1.0 / std::fabs(k)
            << " (z k = " << std::fabs(k) * z << " >= 1)";
    return message.str();
  }
  return "";
}

// The description, built on first use rather than a global: the registry may be read
// while other files are statically initialised.
const DeformerType& spine_type() {
  static const DeformerType type = {
      "spine",
      "the general inextensible spine: a table of tangent angles along x, arc length kept",
      "the tangent angle at each sample, in radians; |theta| <= pi",
      {{"samples",
        {},
        2.0,
        256.0,  // kernels/deformers/spine.cl's FF_SPINE_CHUNK holds 256 / 64 samples
        true,
        32.0,
        "the angles per instance, evenly spaced over the stage's extent in x"}},
      [](const StageOptions& options) { return samples_of(options); },
      [](const StageOptions&, const StageGeometry&) { return kPi; },
      spine_secant,
      "deformers/spine.cl",
      [](const StageOptions&) { return "spine_stage"; },
      [](const StageOptions& options, const StageGeometry& geometry) {
        const double h = spacing(options, geometry);
        return StageConstants{geometry.x_lowest, 1.0 / h, h, double(samples_of(options) - 1)};
      },
      [](const StageOptions& options) { return 8 * samples_of(options); },  // spine.cl's records
      "spine_prepare",
      "spine_stage_from_rest",
      measure_spine,
      check_spine,
      true,  // rest_segments: spine_lanes_segment in spine.cl
      "spine_stage_swept",
  };
  return type;
}

}  // namespace

namespace deformers {
const DeformerType& spine() { return spine_type(); }
}  // namespace deformers

}  // namespace finflex

// The paper's fish bend (METHOD.md section 5): in the stage's frame the spine becomes
// z = m x^2 while keeping its arc length, (12)-(17). One value per instance, m, valid
// for |m| <= 0.5 / x_max (13). Option "mode": the paper's 4th-order series (15)-(17)
// or the exact closed form. OpenCL: kernels/deformers/bend.cl.
#include <algorithm>
#include <cmath>

#include "finflex/deformer_type.hpp"
#include "finflex/error.hpp"
#include "finflex/rig.hpp"

namespace finflex {
namespace {

// The floor on sqrt(1 - 4m^2x^2) where the exact bend's curvature 2m / sqrt(...) is
// infinite (the spine's end at the range limit); the OpenCL kernels use the same floor.
constexpr double kMinSpineCosine = 1e-6;
// 1 - (2mx)^2 below this: near the exact bend's range limit (finflex/accuracy.hpp).
constexpr double kNearLimit = 1e-3;

constexpr std::size_t kMode = 0;  // option index of "mode"

BendMode mode_of(const StageOptions& options) {
  return options[kMode] == 0.0 ? BendMode::kPaper : BendMode::kExact;
}

// Paper: f = (x (1 - 2/3 m^2x^2 - 2/5 m^4x^4), 0, m x^2) (16); df/dx = (a, 0, 2mx) with
// a = 1 - 2m^2x^2 - 2m^4x^4; n = (-2mx, 0, a) / |.| (17); k = (a u' - u a') / g^3 with
// u = 2mx, g = |df/dx|.
SecantSample paper_secant(double x, double m) {
  const double mx2 = m * m * x * x;
  const double a = 1.0 - 2.0 * mx2 - 2.0 * mx2 * mx2;
  const double b = 2.0 * m * x;
  const double da = -4.0 * m * m * x - 8.0 * m * m * m * m * x * x * x;
  const double db = 2.0 * m;
  const double g = std::sqrt(a * a + b * b);
  const double dg = (a * da + b * db) / g;
  SecantSample s;
  s.f = {x * (1.0 - 2.0 / 3.0 * mx2 - 2.0 / 5.0 * mx2 * mx2), 0.0, m * x * x};
  s.df_dx = {a, 0.0, b};
  s.n = glm::dvec3(-b, 0.0, a) / g;
  s.dn_dx = (glm::dvec3(-db, 0.0, da) * g - glm::dvec3(-b, 0.0, a) * dg) / (g * g);
  s.curvature = (a * db - b * da) / (g * g * g);
  return s;
}

// Exact: dx'/dx = sqrt(1 - 4m^2x^2) (13) integrated in closed form,
// x' = x sqrt(1 - 4m^2x^2) / 2 + asin(2mx) / (4m) (-> x as m -> 0);
// unit tangent (c, 0, 2mx), n = (-2mx, 0, c), c = sqrt(1 - 4m^2x^2); k = 2m / c.
SecantSample exact_secant(double x, double m) {
  const double u = std::clamp(2.0 * m * x, -1.0, 1.0);
  const double c = std::sqrt((1.0 - u) * (1.0 + u));
  const double asin_u_over_u = std::fabs(u) < 1e-4 ? 1.0 + u * u / 6.0 : std::asin(u) / u;
  const double c_floor = std::max(c, kMinSpineCosine);
  SecantSample s;
  s.f = {0.5 * x * (c + asin_u_over_u), 0.0, m * x * x};
  s.df_dx = {c, 0.0, u};
  s.n = {-u, 0.0, c};
  s.dn_dx = {-2.0 * m, 0.0, -2.0 * m * u / c_floor};
  s.curvature = 2.0 * m / c_floor;
  s.near_limit = 1.0 - u * u < kNearLimit;
  return s;
}

// The description, built on first use rather than a global: the registry may be read
// while other files are statically initialised.
const DeformerType& bend_type() {
  static const DeformerType type = {
      "bend",
      "the paper's fish bend: the spine becomes z = m x^2, arc length kept (12)-(17)",
      "m, the bend (12); |m| <= 0.5 / x_max (13)",
      {{"mode",
        {"paper", "exact"},
        0.0,
        0.0,
        false,
        1.0,
        "paper: the 4th-order series (15)-(17); exact: the closed form of (13)"}},
      [](const StageOptions&) -> std::size_t { return 1; },
      [](const StageOptions&, const StageGeometry& geometry) { return max_abs_m(geometry.x_max); },
      [](double x, const double* values, const StageOptions& options, const StageGeometry&) {
        return mode_of(options) == BendMode::kExact ? exact_secant(x, values[0])
                                                    : paper_secant(x, values[0]);
      },
      "deformers/bend.cl",
      [](const StageOptions& options) {
        return mode_of(options) == BendMode::kExact ? "bend_exact_stage" : "bend_paper_stage";
      },
      [](const StageOptions&, const StageGeometry&) { return StageConstants{}; },
  };
  return type;
}

}  // namespace

namespace deformers {
const DeformerType& bend() { return bend_type(); }
}  // namespace deformers

const char* to_string(BendMode mode) { return mode == BendMode::kExact ? "exact" : "paper"; }

BendMode parse_bend_mode(const std::string& text, const std::string& field) {
  if (text == "paper") return BendMode::kPaper;
  if (text == "exact") return BendMode::kExact;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not a bend mode (expected paper or exact)");
}

double max_abs_m(double x_max) { return 0.5 / x_max; }

}  // namespace finflex

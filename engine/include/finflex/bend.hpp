// The fish bend of the paper (METHOD.md section 5): settings and parameter checks.
//
// In the body frame (x along the spine, lengths divided by s_x) the secant plane z = 0
// is bent so that the spine becomes z = m x^2 while keeping its arc length (12)-(13).
// m sets the amount and the side of the bend; it is valid for |m| <= 0.5 / x_max (13),
// x_max the largest |x| of the mesh in the body frame.
#pragma once

#include <string>
#include <vector>

namespace finflex {

enum class BendMode {
  kPaper,  // the paper's 4th-order Maclaurin series (15)-(17): no arcsin
  kExact,  // the closed-form integral of (13): x' = x sqrt(1 - 4m^2x^2)/2 + asin(2mx)/(4m)
};

enum class NormalMode {
  kRotate,    // the paper's (8): rotate by R, the rotation taking e_z to the secant normal
  kJacobian,  // exact: transform by the cofactor of the deformation's Jacobian (METHOD.md 6)
};

struct BendSettings {
  BendMode mode = BendMode::kPaper;
  NormalMode normals = NormalMode::kRotate;
};

const char* to_string(BendMode mode);
const char* to_string(NormalMode mode);
// Parse "paper" / "exact" and "rotate" / "jacobian"; errors name `field` and the value.
BendMode parse_bend_mode(const std::string& text, const std::string& field = "mode");
NormalMode parse_normal_mode(const std::string& text, const std::string& field = "normals");

// The largest valid |m| for a mesh whose largest |x| in the body frame is x_max (13).
double max_abs_m(double x_max);

// Checks per-instance bend parameters and returns them ready for a deformer.
// NaN or Inf: kInvalidArgument "m[i] is NaN". |m| above max_abs_m(x_max) (beyond float
// rounding): kOutOfRange naming m[i], its value and the allowed range, unless `clamp`,
// in which case the value is clamped into the range. An empty list: kInvalidArgument.
std::vector<float> checked_bend_params(const std::vector<float>& m, double x_max, bool clamp);

// The same, written into `out` (resized to m.size(); its capacity is reused, so a
// caller checking every frame allocates nothing after the first). On error `out`
// holds an unspecified prefix.
void check_bend_params_into(const std::vector<float>& m, double x_max, bool clamp,
                            std::vector<float>& out);

}  // namespace finflex

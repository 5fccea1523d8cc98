#include <array>
#include <cmath>
#include <sstream>

#include "finflex/bend.hpp"
#include "finflex/error.hpp"
#include "param_bounds.hpp"

namespace finflex {

const char* to_string(BendMode mode) { return mode == BendMode::kExact ? "exact" : "paper"; }

const char* to_string(NormalMode mode) {
  return mode == NormalMode::kJacobian ? "jacobian" : "rotate";
}

BendMode parse_bend_mode(const std::string& text, const std::string& field) {
  if (text == "paper") return BendMode::kPaper;
  if (text == "exact") return BendMode::kExact;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not a bend mode (expected paper or exact)");
}

NormalMode parse_normal_mode(const std::string& text, const std::string& field) {
  if (text == "rotate") return NormalMode::kRotate;
  if (text == "jacobian") return NormalMode::kJacobian;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not a normal mode (expected rotate or jacobian)");
}

double max_abs_m(double x_max) { return 0.5 / x_max; }

std::vector<float> checked_bend_params(const std::vector<float>& m, double x_max, bool clamp) {
  std::vector<float> checked;
  check_bend_params_into(m, x_max, clamp, checked);
  return checked;
}

void check_bend_params_into(const std::vector<float>& m, double x_max, bool clamp,
                            std::vector<float>& checked) {
  if (m.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "m", "m is empty: at least one instance is needed");
  }
  const double limit = max_abs_m(x_max);
  // A float at the limit may round a hair above it; the kernels clamp 2mx into [-1, 1].
  const double accepted = limit * (1.0 + 1e-6);
  const float clamped = std::nextafter(static_cast<float>(limit), 0.0f);
  checked.resize(m.size());
  std::array<float, 16> tile;
  tile.fill(detail::float_bound(accepted));
  if (detail::copy_if_within_bounds(m.data(), m.size(), tile.data(), tile.size(), checked.data())) {
    return;  // the common case, in one vectorised pass
  }
  for (std::size_t i = 0; i < checked.size(); ++i) {
    const float value = checked[i];
    if (!std::isfinite(value)) {
      std::ostringstream message;
      message << "m[" << i << "] is " << (std::isnan(value) ? "NaN" : "infinite");
      throw Error(ErrorCode::kInvalidArgument, "m[" + std::to_string(i) + "]", message.str());
    }
    if (std::fabs(static_cast<double>(value)) <= accepted) continue;
    if (clamp) {
      checked[i] = std::copysign(clamped, value);
      continue;
    }
    std::ostringstream message;
    message.precision(9);
    message << "m[" << i << "] = " << value << " is out of range [" << -limit << ", " << limit
            << "] (|m| <= 0.5 / x_max, x_max = " << x_max << ")";
    throw Error(ErrorCode::kOutOfRange, "m[" + std::to_string(i) + "]", message.str());
  }
}

}  // namespace finflex

#include <algorithm>
#include <cmath>
#include <sstream>

#include "finflex/error.hpp"
#include "finflex/rig_deformer.hpp"
#include "param_bounds.hpp"

namespace finflex {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A float at the limit may round a hair above it; the kernels clamp.
constexpr double kLimitSlack = 1.0 + 1e-6;

}  // namespace

RigParameters::RigParameters(const Rig& rig, std::size_t instance_count)
    : names_(rig.params),
      instance_count_(instance_count),
      values_(instance_count * rig.params.size(), 0.0f) {
  if (instance_count == 0) {
    throw Error(ErrorCode::kInvalidArgument, "instances", "instances = 0: at least one is needed");
  }
}

void RigParameters::set(std::size_t instance, const std::string& name, float value) {
  if (instance >= instance_count_) {
    throw Error(ErrorCode::kInvalidArgument, "instance",
                "instance = " + std::to_string(instance) + " is out of range (" +
                    std::to_string(instance_count_) + " instances)");
  }
  for (std::size_t p = 0; p < names_.size(); ++p) {
    if (names_[p] == name) {
      values_[instance * names_.size() + p] = value;
      return;
    }
  }
  std::string known;
  for (const std::string& n : names_) known += (known.empty() ? "" : ", ") + n;
  throw Error(ErrorCode::kInvalidArgument, name,
              "parameter '" + name + "' is not in the rig (its parameters: " + known + ")");
}

std::vector<double> rig_param_limits(const Rig& rig) {
  std::vector<double> limits(rig.params.size(), kPi);
  std::vector<bool> seen(rig.params.size(), false);
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      const double limit = stage.deformer == DeformerKind::kBend ? max_abs_m(stage.x_max) : kPi;
      limits[stage.param] = seen[stage.param] ? std::min(limits[stage.param], limit) : limit;
      seen[stage.param] = true;
    }
  }
  return limits;
}

void check_rig_params_into(const Rig& rig, const std::vector<double>& limits,
                           const RigParameters& parameters, bool clamp, std::vector<float>& out) {
  detail::check_rig_params_into(rig, limits, detail::rig_bounds_tile(limits), parameters, clamp,
                                out);
}

namespace detail {

std::vector<float> rig_bounds_tile(const std::vector<double>& limits) {
  std::vector<double> accepted(limits.size());
  for (std::size_t p = 0; p < limits.size(); ++p) accepted[p] = limits[p] * kLimitSlack;
  return bounds_tile(accepted);
}

void check_rig_params_into(const Rig& rig, const std::vector<double>& limits,
                           const std::vector<float>& tile, const RigParameters& parameters,
                           bool clamp, std::vector<float>& out) {
  const std::vector<float>& values = parameters.values();
  out.resize(values.size());
  if (parameters.param_count() == rig.params.size() && !values.empty() &&
      copy_if_within_bounds(values.data(), values.size(), tile.data(), tile.size(), out.data())) {
    return;  // the common case, in one vectorised pass
  }
  std::copy(values.begin(), values.end(), out.begin());
  finflex::check_rig_params(rig, limits, parameters, clamp, &out);
}

void check_rig_params(const Rig& rig, const std::vector<double>& limits,
                      const std::vector<float>& tile, const RigParameters& parameters, bool clamp) {
  const std::vector<float>& values = parameters.values();
  if (parameters.param_count() == rig.params.size() && !values.empty() &&
      within_bounds(values.data(), values.size(), tile.data(), tile.size())) {
    return;
  }
  finflex::check_rig_params(rig, limits, parameters, clamp, nullptr);
}

}  // namespace detail

void check_rig_params(const Rig& rig, const std::vector<double>& limits,
                      const RigParameters& parameters, bool clamp, std::vector<float>* clamped) {
  if (parameters.param_count() != rig.params.size()) {
    throw Error(ErrorCode::kInvalidArgument, "parameters",
                "the parameters have " + std::to_string(parameters.param_count()) +
                    " values per instance, the rig " + std::to_string(rig.params.size()));
  }
  const std::size_t count = rig.params.size();
  for (std::size_t i = 0; i < parameters.instance_count(); ++i) {
    for (std::size_t p = 0; p < count; ++p) {
      const float value = parameters.get(i, p);
      if (std::isfinite(value) &&
          std::fabs(static_cast<double>(value)) <= limits[p] * kLimitSlack) {
        continue;
      }
      const std::string field = rig.params[p] + "[" + std::to_string(i) + "]";
      if (!std::isfinite(value)) {
        throw Error(ErrorCode::kInvalidArgument, field,
                    field + " is " + (std::isnan(value) ? "NaN" : "infinite"));
      }
      if (clamp) {
        if (clamped) {
          (*clamped)[i * count + p] =
              std::copysign(std::nextafter(static_cast<float>(limits[p]), 0.0f), value);
        }
        continue;
      }
      std::ostringstream message;
      message.precision(9);
      message << field << " = " << value << " is out of range [" << -limits[p] << ", " << limits[p]
              << "] (the tightest of the stages that read " << rig.params[p] << ")";
      throw Error(ErrorCode::kOutOfRange, field, message.str());
    }
  }
}

const char* to_string(RigPath path) {
  switch (path) {
    case RigPath::kAuto:
      return "auto";
    case RigPath::kFused:
      return "fused";
    case RigPath::kPasses:
      return "passes";
  }
  return "auto";
}

RigPath parse_rig_path(const std::string& text, const std::string& field) {
  if (text == "auto") return RigPath::kAuto;
  if (text == "fused") return RigPath::kFused;
  if (text == "passes") return RigPath::kPasses;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not an execution path (expected auto, fused or passes)");
}

}  // namespace finflex

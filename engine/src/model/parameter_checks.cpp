#include "model/parameter_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "finflex/error.hpp"

namespace finflex::detail {
namespace {

// A float at the limit may round a hair above it; the kernels clamp.
constexpr double kLimitSlack = 1.0 + 1e-6;
constexpr std::size_t kLanes = 16;

// The largest float f with f <= bound, so that for a float v,
// |v| <= f (in float) exactly when |v| <= bound (in double).
float float_bound(double bound) {
  float f = static_cast<float>(bound);
  if (static_cast<double>(f) > bound) f = std::nextafter(f, 0.0f);
  return f;
}

// One branch-free (vectorised) pass over `count` values against `tile` (repeated);
// copies them to `out` when given.
bool scan(const float* values, std::size_t count, const std::vector<float>& tile, float* out) {
  int outside = 0;
  const std::size_t tile_length = tile.size();
  for (std::size_t start = 0; start < count; start += tile_length) {
    const std::size_t length = std::min(tile_length, count - start);
    const float* source = values + start;
    if (out) {
      float* target = out + start;
      for (std::size_t k = 0; k < length; ++k) {
        target[k] = source[k];
        outside |= !(std::fabs(source[k]) <= tile[k]);  // NaN compares false
      }
    } else {
      for (std::size_t k = 0; k < length; ++k) outside |= !(std::fabs(source[k]) <= tile[k]);
    }
  }
  return outside == 0;
}

std::string value_field(const RigParameter& parameter, std::size_t instance, std::size_t k) {
  std::string field = parameter.name + "[" + std::to_string(instance) + "]";
  if (parameter.count > 1) field += "[" + std::to_string(k) + "]";
  return field;
}

}  // namespace

ParameterChecker::ParameterChecker(const Rig& rig)
    : parameters_(rig.parameters), values_per_instance_(rig.values_per_instance()) {
  std::vector<float> row(values_per_instance_);
  for (const RigParameter& parameter : parameters_) {
    for (std::size_t k = 0; k < parameter.count; ++k)
      row[parameter.offset + k] = float_bound(parameter.limit * kLimitSlack);
  }
  for (std::size_t lane = 0; lane < kLanes && !row.empty(); ++lane)
    tile_.insert(tile_.end(), row.begin(), row.end());
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      if (!stage.deformer->check_values) continue;
      stage_checks_.push_back(
          {stage, "the " + std::string(stage.deformer->name) + " of '" + component.name + "'"});
    }
  }
}

void ParameterChecker::check(const ParameterView& view, bool clamp, float* out) const {
  const std::size_t stride = view.stride ? view.stride : values_per_instance_;
  if (values_per_instance_ == 0) return;
  bool within = true;
  if (stride == values_per_instance_) {
    within = scan(view.data, view.instance_count * stride, tile_, out);  // the common case
  } else {
    for (std::size_t i = 0; i < view.instance_count && within; ++i) {
      within = scan(view.data + i * stride, values_per_instance_, tile_,
                    out ? out + i * values_per_instance_ : nullptr);
    }
  }
  if (!within) check_slowly(view, clamp, out);
  if (!stage_checks_.empty()) check_stages(view, clamp, out);
}

// Each instance's values of the stages that check them beyond their range, on the
// checked copy (`out`, which clamping adjusts) or on a scratch copy.
void ParameterChecker::check_stages(const ParameterView& view, bool clamp, float* out) const {
  const std::size_t stride = view.stride ? view.stride : values_per_instance_;
  std::vector<float> scratch;
  for (const StageCheck& check : stage_checks_) {
    const RigParameter& parameter = parameters_[check.stage.param];
    for (std::size_t i = 0; i < view.instance_count; ++i) {
      float* values = nullptr;
      if (out) {
        values = out + i * values_per_instance_ + parameter.offset;
      } else {
        const float* source = view.data + i * stride + parameter.offset;
        scratch.assign(source, source + parameter.count);
        values = scratch.data();
      }
      const std::string problem = check.stage.deformer->check_values(values, check.stage.options,
                                                                     check.stage.geometry, clamp);
      if (problem.empty()) continue;
      const std::string field = parameter.name + "[" + std::to_string(i) + "]";
      throw Error(ErrorCode::kOutOfRange, field, field + ": " + problem + " (" + check.where + ")");
    }
  }
}

void ParameterChecker::check(const ParameterView& view, bool clamp) const {
  check(view, clamp, nullptr);
}

void ParameterChecker::check_slowly(const ParameterView& view, bool clamp, float* out) const {
  const std::size_t stride = view.stride ? view.stride : values_per_instance_;
  for (std::size_t i = 0; i < view.instance_count; ++i) {
    const float* row = view.data + i * stride;
    for (const RigParameter& parameter : parameters_) {
      for (std::size_t k = 0; k < parameter.count; ++k) {
        const std::size_t at = parameter.offset + k;
        const float value = row[at];
        if (out) out[i * values_per_instance_ + at] = value;
        if (std::isfinite(value) &&
            std::fabs(static_cast<double>(value)) <= parameter.limit * kLimitSlack) {
          continue;
        }
        const std::string field = value_field(parameter, i, k);
        if (!std::isfinite(value)) {
          throw Error(ErrorCode::kInvalidArgument, field,
                      field + " is " + (std::isnan(value) ? "NaN" : "infinite"));
        }
        if (clamp) {
          if (out) {
            out[i * values_per_instance_ + at] =
                std::copysign(std::nextafter(static_cast<float>(parameter.limit), 0.0f), value);
          }
          continue;
        }
        std::ostringstream message;
        message.precision(9);
        message << field << " = " << value << " is out of range [" << -parameter.limit << ", "
                << parameter.limit << "] (" << parameter.limit_source << ")";
        throw Error(ErrorCode::kOutOfRange, field, message.str());
      }
    }
  }
}

}  // namespace finflex::detail

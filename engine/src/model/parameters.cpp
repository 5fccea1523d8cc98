#include "finflex/parameters.hpp"

#include <string>

#include "finflex/error.hpp"
#include "model/parameter_checks.hpp"

namespace finflex {

RigParameters::RigParameters(const Rig& rig, std::size_t instance_count)
    : parameters_(rig.parameters),
      instance_count_(instance_count),
      values_per_instance_(rig.values_per_instance()) {
  if (instance_count == 0) {
    throw Error(ErrorCode::kInvalidArgument, "instances", "instances = 0: at least one is needed");
  }
  values_.assign(instance_count * values_per_instance_, 0.0f);
}

std::size_t RigParameters::index_of(const std::string& name) const {
  for (std::size_t p = 0; p < parameters_.size(); ++p) {
    if (parameters_[p].name == name) return p;
  }
  std::string known;
  for (const RigParameter& p : parameters_) known += (known.empty() ? "" : ", ") + p.name;
  throw Error(ErrorCode::kInvalidArgument, name,
              "parameter '" + name + "' is not in the rig (its parameters: " + known + ")");
}

void RigParameters::check_instance(std::size_t instance) const {
  if (instance >= instance_count_) {
    throw Error(ErrorCode::kInvalidArgument, "instance",
                "instance = " + std::to_string(instance) + " is out of range (" +
                    std::to_string(instance_count_) + " instances)");
  }
}

void RigParameters::set(std::size_t instance, const std::string& name, float value) {
  set(instance, name, std::vector<float>{value});
}

void RigParameters::set(std::size_t instance, const std::string& name,
                        const std::vector<float>& values) {
  check_instance(instance);
  const RigParameter& parameter = parameters_[index_of(name)];
  if (values.size() != parameter.count) {
    throw Error(ErrorCode::kInvalidArgument, name,
                "parameter '" + name + "' takes " + std::to_string(parameter.count) +
                    " values, not " + std::to_string(values.size()));
  }
  std::copy(values.begin(), values.end(),
            values_.begin() +
                static_cast<std::ptrdiff_t>(instance * values_per_instance_ + parameter.offset));
}

float RigParameters::get(std::size_t instance, std::size_t parameter) const {
  check_instance(instance);
  if (parameter >= parameters_.size()) {
    throw Error(ErrorCode::kInvalidArgument, "parameter",
                "parameter = " + std::to_string(parameter) + " is out of range (" +
                    std::to_string(parameters_.size()) + " parameters)");
  }
  return values_[instance * values_per_instance_ + parameters_[parameter].offset];
}

void check_parameters(const Rig& rig, const ParameterView& view, bool clamp, float* out) {
  detail::ParameterChecker(rig).check(view, clamp, out);
}

}  // namespace finflex

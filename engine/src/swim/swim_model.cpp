// SwimModel (finflex/swim.hpp): a rigged mesh checked as a swim rig, with the spine's
// samples and fold limits measured once.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "finflex/error.hpp"
#include "finflex/swim.hpp"

namespace finflex {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

// The parameter's offset when it is a one-value parameter read by hinges only; kNone
// when the name is empty or the rig has no such parameter.
std::size_t fin_offset(const Rig& rig, const std::string& name, const std::string& field) {
  if (name.empty()) return SwimModel::kNone;
  for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
    if (rig.parameters[p].name != name) continue;
    for (const RigComponent& component : rig.components) {
      for (const RigStage& stage : component.chain) {
        if (stage.param == p && std::string(stage.deformer->name) != "hinge") {
          fail(field, "'" + name + "' is read by a " + stage.deformer->name + " stage of '" +
                          component.name + "', not by a fin's hinge");
        }
      }
    }
    return rig.parameters[p].offset;
  }
  return SwimModel::kNone;
}

void check_kinematics(const SwimKinematics& k) {
  const std::pair<const char*, double> positive[] = {
      {"frequency_size", k.frequency_size},
      {"wavelength", k.wavelength},
      {"max_turn_curvature", k.max_turn_curvature},
      {"min_turn_speed", k.min_turn_speed},
      {"fold_margin", k.fold_margin},
      {"pectoral_hover_speed", k.pectoral_hover_speed}};
  for (const auto& [name, value] : positive) {
    if (!std::isfinite(value) || !(value > 0.0)) {
      fail(std::string("swim.kinematics.") + name, std::to_string(value) + " must be > 0");
    }
  }
  const std::pair<const char*, double> finite[] = {{"frequency_speed", k.frequency_speed},
                                                   {"envelope[0]", k.envelope[0]},
                                                   {"envelope[1]", k.envelope[1]},
                                                   {"envelope[2]", k.envelope[2]},
                                                   {"amplitude_base", k.amplitude_base},
                                                   {"amplitude_speed", k.amplitude_speed},
                                                   {"amplitude_min", k.amplitude_min},
                                                   {"caudal_amplitude", k.caudal_amplitude},
                                                   {"peduncle", k.peduncle},
                                                   {"pectoral_rest", k.pectoral_rest},
                                                   {"pectoral_amplitude", k.pectoral_amplitude}};
  for (const auto& [name, value] : finite) {
    if (!std::isfinite(value)) fail(std::string("swim.kinematics.") + name, "is not finite");
  }
  if (k.fold_margin >= 1.0) fail("swim.kinematics.fold_margin", "must be below 1");
}

}  // namespace

SwimModel::SwimModel(const RiggedMesh& model, const SwimKinematics& kinematics,
                     const SwimBinding& binding)
    : model_(model), kinematics_(kinematics) {
  check_kinematics(kinematics_);
  const Rig& rig = model_.rig();
  const RigStage* wave = nullptr;
  for (const RigStage& stage : rig.components.front().chain) {
    if (std::string(stage.deformer->name) == "spine" &&
        rig.parameters[stage.param].name == binding.wave) {
      wave = &stage;
    }
  }
  if (wave == nullptr) {
    fail("swim.wave", "the rig has no spine stage on its root component '" +
                          rig.components.front().name + "' reading '" + binding.wave +
                          "': a swim rig needs a body (docs/swimming.md)");
  }
  const RigParameter& parameter = rig.parameters[wave->param];
  wave_offset_ = parameter.offset;
  samples_ = parameter.count;
  const StageGeometry& geometry = wave->geometry;
  x_first_ = geometry.x_lowest;
  spacing_ = (geometry.x_highest - geometry.x_lowest) / double(samples_ - 1);
  // Fold limits per segment from the spine's measurements (largest z each side).
  const std::size_t segments = samples_ - 1;
  for (std::size_t j = 0; j < segments; ++j) {
    const double up = geometry.measurements[j], down = geometry.measurements[segments + j];
    const double unlimited = std::numeric_limits<double>::max();
    max_positive_.push_back(up > 0.0 ? kinematics_.fold_margin / up : unlimited);
    max_negative_.push_back(down > 0.0 ? kinematics_.fold_margin / down : unlimited);
  }
  tail_offset_ = fin_offset(rig, binding.tail, "swim.tail");
  right_offset_ = fin_offset(rig, binding.right_pectoral, "swim.right_pectoral");
  left_offset_ = fin_offset(rig, binding.left_pectoral, "swim.left_pectoral");
}

std::vector<double> SwimModel::value_bounds() const {
  const Rig& rig = model_.rig();
  std::vector<double> bounds;
  const SwimKinematics& k = kinematics_;
  for (const RigParameter& parameter : rig.parameters) {
    double bound = parameter.limit;
    if (parameter.offset == tail_offset_) {
      bound = std::min(bound, k.caudal_amplitude);
    } else if (parameter.offset == right_offset_ || parameter.offset == left_offset_) {
      bound = std::min(bound, std::fabs(k.pectoral_rest) + k.pectoral_amplitude);
    }
    bounds.push_back(bound);
  }
  return bounds;
}

}  // namespace finflex

// SwimReference (finflex/swim.hpp): the swim driver on the CPU in double precision.
#include <cmath>
#include <string>

#include "finflex/error.hpp"
#include "finflex/swim.hpp"
#include "swim/kinematics.hpp"

namespace finflex {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + " " + message);
}

double wrapped(double phase) { return phase - std::floor(phase); }

}  // namespace

void swim_inputs_from_rows(const float* rows, std::size_t fish, std::vector<SwimInput>& inputs) {
  inputs.resize(fish);
  swim_inputs_from_rows(rows, fish, inputs.data());
}

void swim_inputs_from_rows(const float* rows, std::size_t fish, SwimInput* inputs) {
  for (std::size_t i = 0; i < fish; ++i) {
    const float* row = rows + 7 * i;
    inputs[i].position = {row[0], row[1], row[2]};
    inputs[i].yaw = row[3];
    inputs[i].pitch = row[4];
    inputs[i].speed = row[5];
    inputs[i].turn_rate = row[6];
  }
}

void check_swim_inputs(const std::vector<SwimInput>& inputs, std::size_t fish, double dt) {
  check_swim_inputs(inputs.data(), inputs.size(), fish, dt);
}

void check_swim_inputs(const SwimInput* inputs, std::size_t count, std::size_t fish, double dt) {
  if (!std::isfinite(dt) || !(dt > 0.0)) fail("dt", "= " + std::to_string(dt) + " must be > 0");
  if (count != fish) {
    fail("inputs",
         "has " + std::to_string(count) + " entries for " + std::to_string(fish) + " fish");
  }
  for (std::size_t i = 0; i < count; ++i) {
    const SwimInput& in = inputs[i];
    // The common case in one pass of comparisons; names only for a bad value.
    const bool finite = std::isfinite(in.position.x) && std::isfinite(in.position.y) &&
                        std::isfinite(in.position.z) && std::isfinite(in.yaw) &&
                        std::isfinite(in.pitch) && std::isfinite(in.speed) &&
                        std::isfinite(in.turn_rate);
    if (finite && in.speed >= 0.0f) continue;
    const std::string at = "inputs[" + std::to_string(i) + "].";
    const std::pair<const char*, float> values[] = {
        {"position.x", in.position.x}, {"position.y", in.position.y},
        {"position.z", in.position.z}, {"yaw", in.yaw},
        {"pitch", in.pitch},           {"speed", in.speed},
        {"turn_rate", in.turn_rate}};
    for (const auto& [name, value] : values) {
      if (!std::isfinite(value)) fail(at + name, "is not finite");
    }
    if (in.speed < 0.0f) fail(at + "speed", "= " + std::to_string(in.speed) + " is negative");
  }
}

SwimReference::SwimReference(const SwimModel& swim, const std::vector<float>& lengths,
                             const std::vector<float>& phases)
    : swim_(&swim),
      lengths_(lengths),
      parameters_(swim.model(), std::max<std::size_t>(lengths.size(), 1)) {
  if (lengths.empty()) fail("lengths", "is empty: at least one fish is needed");
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    if (!std::isfinite(lengths[i]) || !(lengths[i] > 0.0f)) {
      fail("lengths[" + std::to_string(i) + "]",
           "= " + std::to_string(lengths[i]) + " must be finite and > 0");
    }
  }
  if (!phases.empty() && phases.size() != lengths.size()) {
    fail("phases", "has " + std::to_string(phases.size()) + " entries for " +
                       std::to_string(lengths.size()) + " fish");
  }
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const double phase = phases.empty() ? 0.0 : double(phases[i]);
    if (!std::isfinite(phase)) fail("phases[" + std::to_string(i) + "]", "is not finite");
    wave_phases_.push_back(wrapped(phase));
    pectoral_phases_.push_back(wrapped(phase));
  }
  frequencies_.assign(lengths.size(), 0.0);
  placements_.resize(lengths.size());
}

void SwimReference::step(const std::vector<SwimInput>& inputs, double dt) {
  check_swim_inputs(inputs, lengths_.size(), dt);
  const SwimModel& swim = *swim_;
  const SwimKinematics& k = swim.kinematics();
  const std::size_t per_instance = parameters_.values_per_instance();
  std::vector<double> theta(swim.samples());
  limited_segments_ = 0;
  for (std::size_t i = 0; i < lengths_.size(); ++i) {
    const SwimInput& in = inputs[i];
    const double length = lengths_[i];
    const double speed = in.speed;
    const double f = detail::tail_beat_frequency(k, length, speed);
    frequencies_[i] = f;
    // Phases integrate the frequency: no jump when it changes.
    wave_phases_[i] = wrapped(wave_phases_[i] + f * dt);
    pectoral_phases_[i] = wrapped(pectoral_phases_[i] + f * dt);
    const double scale = detail::amplitude_scale(k, length, speed);
    const double curvature = detail::turn_curvature(k, length, speed, in.turn_rate);
    limited_segments_ += detail::wave_angles(swim, wave_phases_[i], scale, curvature, theta.data());
    float* row = parameters_.values().data() + i * per_instance;
    for (std::size_t j = 0; j < theta.size(); ++j)
      row[swim.wave_offset() + j] = static_cast<float>(theta[j]);
    if (swim.tail_offset() != SwimModel::kNone) {
      row[swim.tail_offset()] = static_cast<float>(detail::caudal_angle(k, wave_phases_[i], scale));
    }
    const double pectoral = detail::pectoral_amplitude(k, length, speed);
    const double beat = std::sin(kTwoPi * pectoral_phases_[i]);
    if (swim.right_pectoral_offset() != SwimModel::kNone) {
      row[swim.right_pectoral_offset()] = static_cast<float>(k.pectoral_rest + pectoral * beat);
    }
    if (swim.left_pectoral_offset() != SwimModel::kNone) {
      row[swim.left_pectoral_offset()] = static_cast<float>(k.pectoral_rest - pectoral * beat);
    }
    placements_[i] = detail::swim_placement(in, lengths_[i]);
  }
}

}  // namespace finflex

#include "swim/kinematics.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace finflex::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

}  // namespace

double tail_beat_frequency(const SwimKinematics& k, double length, double speed) {
  return k.frequency_size * std::cbrt(1.0 / (100.0 * length)) + k.frequency_speed * speed / length;
}

double amplitude_scale(const SwimKinematics& k, double length, double speed) {
  return std::clamp(k.amplitude_base + k.amplitude_speed * speed / length, k.amplitude_min, 1.0);
}

double turn_curvature(const SwimKinematics& k, double length, double speed, double turn_rate) {
  const double curvature = -turn_rate * length / std::max(speed, k.min_turn_speed);
  return std::clamp(curvature, -k.max_turn_curvature, k.max_turn_curvature);
}

std::size_t wave_angles(const SwimModel& swim, double phase, double scale, double curvature,
                        double* theta) {
  const SwimKinematics& k = swim.kinematics();
  const std::size_t n = swim.samples();
  const double x_snout = swim.x_snout();
  const double extent = x_snout - swim.sample_x(0);
  const double wave_number = kTwoPi / k.wavelength;
  for (std::size_t j = 0; j < n; ++j) {
    const double x = swim.sample_x(j);
    const double xi = (x_snout - x) / extent;
    const double envelope = k.envelope[0] + xi * (k.envelope[1] + xi * k.envelope[2]);
    const double envelope_slope = k.envelope[1] + 2.0 * xi * k.envelope[2];
    const double psi = wave_number * xi - kTwoPi * phase;
    // dh/dxi of h = scale A(xi) sin(psi); dh/dx = -dh/dxi / extent.
    const double dh_dxi =
        scale * (envelope_slope * std::sin(psi) + envelope * wave_number * std::cos(psi));
    theta[j] = std::atan(-dh_dxi / extent) + curvature * x;
  }
  // Keep every segment clear of folding (METHOD.md section 6): bend it less and turn
  // the rest of the spine with it.
  std::size_t limited = 0;
  const double h = swim.spacing();
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double bend = (theta[j + 1] - theta[j]) / h;
    const double allowed = bend > 0.0 ? swim.max_bend_positive()[j] : -swim.max_bend_negative()[j];
    if (std::fabs(bend) <= std::fabs(allowed)) continue;
    const double shift = (allowed - bend) * h;
    for (std::size_t after = j + 1; after < n; ++after) theta[after] += shift;
    ++limited;
  }
  return limited;
}

double caudal_angle(const SwimKinematics& k, double phase, double scale) {
  return k.caudal_amplitude * scale * std::cos(kTwoPi * (k.peduncle / k.wavelength - phase));
}

double pectoral_amplitude(const SwimKinematics& k, double length, double speed) {
  return k.pectoral_amplitude * std::clamp(1.0 - speed / length / k.pectoral_hover_speed, 0.0, 1.0);
}

Placement swim_placement(const SwimInput& input, float length) {
  Placement placement;
  placement.position = input.position;
  placement.orientation = glm::angleAxis(input.yaw, glm::vec3(0.0f, 1.0f, 0.0f)) *
                          glm::angleAxis(input.pitch, glm::vec3(0.0f, 0.0f, 1.0f));
  placement.length = length;
  return placement;
}

}  // namespace finflex::detail

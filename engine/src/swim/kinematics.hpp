// The swimming kinematics of one fish in one frame (finflex/swim.hpp), in double
// precision: what SwimReference computes and kernels/swim/driver.cl mirrors in float.
#pragma once

#include <cstddef>

#include "finflex/swim.hpp"

namespace finflex::detail {

// Tail-beat frequency (Hz) of a fish of length L (m) at speed U (m/s) through the water:
// f = a L_cm^(-1/3) + b U / L (Webb, Kostecki & Stevens 1984).
double tail_beat_frequency(const SwimKinematics& k, double length, double speed);

// The envelope's scale: clamp(base + speed_gain U / L, minimum, 1).
double amplitude_scale(const SwimKinematics& k, double length, double speed);

// The turning bend's curvature per body length: -turn_rate L / max(U, min_turn_speed),
// at most max_turn_curvature each way (a left turn, turn_rate > 0, bends the body
// concave to its left, towards -z).
double turn_curvature(const SwimKinematics& k, double length, double speed, double turn_rate);

// The spine's angles theta_k at the swim model's samples (root frame, lengths in body
// lengths): atan of the travelling wave's slope, h(xi) = scale A(xi) sin(2 pi (xi /
// wavelength - phase)), xi = (x_snout - x) / extent, plus the turning bend curvature x;
// each segment's bend then limited to clear folding. Returns the segments limited.
std::size_t wave_angles(const SwimModel& swim, double phase, double scale, double curvature,
                        double* theta);

// The caudal fin's angle: trailing the peduncle by a quarter beat.
double caudal_angle(const SwimKinematics& k, double phase, double scale);

// The pectoral fins' amplitude: beating below the hover speed.
double pectoral_amplitude(const SwimKinematics& k, double length, double speed);

// The placement of a fish at `input` of `length`.
Placement swim_placement(const SwimInput& input, float length);

}  // namespace finflex::detail

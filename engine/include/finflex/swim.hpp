// Swimming: each frame, a fish's motion (speed through the water, turning rate, pose)
// becomes the parameters of its swim rig and its world placement: a carangiform
// travelling body wave on the body's spine with the turning bend added to it, the
// caudal fin trailing the peduncle, the pectoral fins beating when the fish is slow
// (METHOD.md section 6; the kinematics and their sources: docs/swimming.md).
//
// A swim rig is a rig whose root component has a `spine` stage (finflex/rig.hpp)
// reading the wave parameter, and optionally hinges on the caudal and pectoral fins:
// data/rigs/*_swim.rig.json.
//
//   SwimModel swim(model);                         // the rig checked, tables prepared
//   SwimReference fish(swim, lengths);            // CPU, double; or ClSwimDriver (GPU)
//   fish.step(inputs, dt);                         // phases advance by f dt
//   run the job with fish.parameters() and fish.placements()
//
// Each fish's wave and fin phases are integrated over time (phase += f dt), so a change
// of speed changes the tail-beat frequency without making the wave jump or rewind.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/export.hpp"
#include "finflex/model.hpp"
#include "finflex/parameters.hpp"
#include "finflex/placement.hpp"

namespace finflex {

// The kinematics (defaults and their sources in docs/swimming.md). L is the fish's
// length (m), U its speed through the water (m/s), U / L in body lengths per second.
struct SwimKinematics {
  // Tail-beat frequency f = frequency_size L_cm^(-1/3) + frequency_speed U / L (Hz):
  // Webb, Kostecki & Stevens 1984, rainbow trout of 5.5-56 cm.
  double frequency_size = 3.19;
  double frequency_speed = 1.29;
  // The midline's lateral half-amplitude A(xi) / L = envelope[0] + envelope[1] xi +
  // envelope[2] xi^2, xi from the snout (0) to the tail (1): the quadratic fitted by
  // Borazjani & Sotiropoulos 2008 to Videler & Hess 1984. Tail tip 0.10 L.
  double envelope[3] = {0.02, -0.0825, 0.1625};
  // The envelope's scale with speed: clamp(amplitude_base + amplitude_speed U / L,
  // amplitude_min, 1): 0.75 at 1 body length per second (tail tip 0.15 L peak to peak,
  // Webb et al. 1984), 1 (0.20 L, Bainbridge 1958's maximum) from 1.67.
  double amplitude_base = 0.6;
  double amplitude_speed = 0.15;
  double amplitude_min = 0.6;
  // The body wave's length in body lengths: 0.80 for salmonids (Webb 1971, Webb et
  // al. 1984); 0.95 for carangiform fish (Videler & Hess 1984).
  double wavelength = 0.80;
  // Turning: the body bends into a C of curvature turn_rate / U (1 / m), at most
  // max_turn_curvature per body length (a turning radius of 0.2 L: Webb 1983 measured
  // 0.18 L for trout); below min_turn_speed (m/s) the curvature uses that speed.
  double max_turn_curvature = 5.0;
  double min_turn_speed = 0.05;
  // The caudal fin's angle (radians) trails the peduncle (at xi = peduncle) by a quarter
  // of a beat: caudal_amplitude times the envelope's scale (Jayne & Lauder 1995).
  double caudal_amplitude = 0.35;
  double peduncle = 0.85;
  // Pectoral fins: held at pectoral_rest (radians, the rig's sign: > 0 opens the fin) at
  // cruise (Drucker & Lauder 2003: adducted from 0.5 body lengths per second); below
  // pectoral_hover_speed body lengths per second they beat, alternately, up to
  // pectoral_amplitude, at the tail-beat frequency.
  double pectoral_rest = 0.0;
  double pectoral_amplitude = 0.5;
  double pectoral_hover_speed = 0.5;
  // A segment of the spine is never bent beyond fold_margin of the curvature that
  // would fold the surface through itself (z k < fold_margin for its vertices).
  double fold_margin = 0.95;
};

// Which parameters of the rig the driver writes. `wave` must be read by a spine stage
// of the root component; the others are driven when the rig has them (empty: never).
struct SwimBinding {
  std::string wave = "body_wave";
  std::string tail = "tail_angle";
  std::string right_pectoral = "right_pectoral_angle";
  std::string left_pectoral = "left_pectoral_angle";
};

// One fish in one frame, from the simulation.
struct SwimInput {
  glm::vec3 position{0.0f};  // the body frame's origin (the pivot), world units (m), y up
  float yaw = 0.0f;          // heading about world +y, radians: 0 towards +x, pi/2 towards -z
  float pitch = 0.0f;        // nose up, radians
  float speed = 0.0f;        // through the water, m/s, >= 0
  float turn_rate = 0.0f;    // d yaw / dt, rad/s: > 0 turns to the fish's left
};

// A model made ready to swim: its binding checked, the spine's sample positions and
// fold limits measured once.
class FINFLEX_API SwimModel {
 public:
  // kInvalidArgument: field "swim.wave" when the rig has no such parameter or no spine
  // stage on its root reads it ("a rig without a body"); "swim.tail" etc. when a named
  // fin parameter is not a one-value parameter of a hinge; "swim.kinematics.<name>"
  // for a kinematic value out of its domain.
  explicit SwimModel(const RiggedMesh& model, const SwimKinematics& kinematics = {},
                     const SwimBinding& binding = {});

  const RiggedMesh& model() const { return model_; }
  const SwimKinematics& kinematics() const { return kinematics_; }

  // The wave's table: its offset in a parameter row, sample count, sample positions in
  // the root frame (x_0 = tail end ... x_{n-1} = snout), and per segment the largest
  // curvature each way that stays fold_margin clear of folding.
  std::size_t wave_offset() const { return wave_offset_; }
  std::size_t samples() const { return samples_; }
  double sample_x(std::size_t k) const { return x_first_ + spacing_ * double(k); }
  double spacing() const { return spacing_; }
  double x_snout() const { return x_first_ + spacing_ * double(samples_ - 1); }
  const std::vector<double>& max_bend_positive() const { return max_positive_; }
  const std::vector<double>& max_bend_negative() const { return max_negative_; }
  // Offsets of the fin angles in a row; kNone when the rig does not have them.
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t tail_offset() const { return tail_offset_; }
  std::size_t right_pectoral_offset() const { return right_offset_; }
  std::size_t left_pectoral_offset() const { return left_offset_; }
  // Per parameter of the rig (Rig::parameters), the largest |value| the swim gives it:
  // the caudal fin's caudal_amplitude, a pectoral fin's |pectoral_rest| +
  // pectoral_amplitude (each within the parameter's limit), the rest their limits.
  // For LevelOptions::value_bounds.
  std::vector<double> value_bounds() const;

 private:
  RiggedMesh model_;
  SwimKinematics kinematics_;
  std::size_t wave_offset_ = 0;
  std::size_t samples_ = 0;
  double x_first_ = 0.0;
  double spacing_ = 1.0;
  std::vector<double> max_positive_, max_negative_;
  std::size_t tail_offset_ = kNone, right_offset_ = kNone, left_offset_ = kNone;
};

// The driver on the CPU in double precision: the reference the device driver is
// tested against, and a driver for users without OpenCL.
class FINFLEX_API SwimReference {
 public:
  // One fish per length (m, > 0). Phases start at `phases` (cycles, one per fish) or 0.
  // kInvalidArgument naming "lengths[i]" or "phases" for bad values.
  SwimReference(const SwimModel& swim, const std::vector<float>& lengths,
                const std::vector<float>& phases = {});

  // One frame: every fish's phases advance by its frequency times dt (s, > 0), then its
  // parameters and placement are written. kInvalidArgument naming "dt" or
  // "inputs[i].<field>" (a non-finite value, a negative speed) or "inputs" (a count
  // that is not the fish count); nothing changes on error.
  void step(const std::vector<SwimInput>& inputs, double dt);

  std::size_t fish_count() const { return lengths_.size(); }
  const RigParameters& parameters() const { return parameters_; }
  const std::vector<Placement>& placements() const { return placements_; }
  const std::vector<double>& wave_phases() const { return wave_phases_; }
  const std::vector<double>& pectoral_phases() const { return pectoral_phases_; }
  // Tail-beat frequency of each fish in the last step (Hz).
  const std::vector<double>& frequencies() const { return frequencies_; }
  // Spine segments bent less than asked in the last step, to keep clear of folding.
  std::size_t limited_segments() const { return limited_segments_; }

 private:
  const SwimModel* swim_;
  std::vector<float> lengths_;
  std::vector<double> wave_phases_, pectoral_phases_, frequencies_;
  RigParameters parameters_;
  std::vector<Placement> placements_;
  std::size_t limited_segments_ = 0;
};

// Checks one frame's inputs: kInvalidArgument naming "inputs" (a count other than
// `fish`) or "inputs[i].<field>" (not finite; a negative speed), and "dt" (not finite
// and > 0).
FINFLEX_API void check_swim_inputs(const std::vector<SwimInput>& inputs, std::size_t fish,
                                   double dt);
// The same for `count` inputs from `inputs`.
FINFLEX_API void check_swim_inputs(const SwimInput* inputs, std::size_t count, std::size_t fish,
                                   double dt);

// Swim inputs from rows of 7 floats (x, y, z, yaw, pitch, speed, turning rate: a
// SwimInput's fields in order), the form arrays and files carry them in; `fish` rows.
FINFLEX_API void swim_inputs_from_rows(const float* rows, std::size_t fish,
                                       std::vector<SwimInput>& inputs);
// The same into `fish` SwimInputs at `inputs` (ClSwimDriver::staged_inputs()).
FINFLEX_API void swim_inputs_from_rows(const float* rows, std::size_t fish, SwimInput* inputs);

}  // namespace finflex

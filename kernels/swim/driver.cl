/* The swim driver (finflex/cl_swim.hpp): one work-item per fish advances its phases
 * by its tail-beat frequency times dt and writes its swim rig's parameters (the
 * spine's angles, the fin angles) and its world placement record, as SwimReference
 * does in double precision (engine/src/swim/kinematics.cpp has the formulas and their
 * sources). Generated before this file (engine/src/swim/cl_swim_driver.cpp):
 *   FF_SWIM_SAMPLES, FF_SWIM_VALUES (values per instance), FF_SWIM_WAVE, FF_SWIM_TAIL,
 *   FF_SWIM_RIGHT, FF_SWIM_LEFT (offsets in a row; -1: not driven), FF_SWIM_X_FIRST,
 *   FF_SWIM_SPACING, FF_SWIM_EXTENT, the kinematics FF_K_* and the per-segment bend
 *   limits swim_max_positive[] and swim_max_negative[].
 *
 * inputs:   7 floats per fish: position (3), yaw, pitch, speed, turn rate (SwimInput)
 * lengths:  the fish's length (m)
 * phases:   2 floats per fish, read and written: the wave's and the pectoral fins'
 * params:   FF_SWIM_VALUES floats per fish (slots not driven keep their values)
 * placements: 16 floats per fish (kernels/common/placement.cl's record)
 * limited:  per fish, the spine segments bent less than asked (to clear folding) */
#define FF_TWO_PI 6.28318530717958647692f

inline float swim_wrapped(float phase) { return phase - floor(phase); }

__kernel void swim_drive(__global const float* restrict inputs,
                         __global const float* restrict lengths,
                         __global float* restrict phases, __global float* restrict params,
                         __global float* restrict placements, __global uint* restrict limited,
                         const float dt, const uint fish) {
  const size_t i = get_global_id(0);
  if (i >= fish) return;
  __global const float* in = inputs + i * 7;
  const float length = lengths[i];
  const float speed = in[5];
  const float body_lengths = speed / length;
  /* Tail-beat frequency (Webb, Kostecki & Stevens 1984); phases integrate it. */
  const float frequency =
      FF_K_FREQUENCY_SIZE * cbrt(1.0f / (100.0f * length)) + FF_K_FREQUENCY_SPEED * body_lengths;
  const float phase = swim_wrapped(phases[2 * i] + frequency * dt);
  const float fin_phase = swim_wrapped(phases[2 * i + 1] + frequency * dt);
  phases[2 * i] = phase;
  phases[2 * i + 1] = fin_phase;
  const float scale =
      clamp(FF_K_AMPLITUDE_BASE + FF_K_AMPLITUDE_SPEED * body_lengths, FF_K_AMPLITUDE_MIN, 1.0f);
  const float curvature = clamp(-in[6] * length / fmax(speed, FF_K_MIN_TURN_SPEED),
                                -FF_K_MAX_TURN_CURVATURE, FF_K_MAX_TURN_CURVATURE);

  /* The spine's angles: the travelling wave's slope and the turning bend. */
  float theta[FF_SWIM_SAMPLES];
  const float x_snout = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)(FF_SWIM_SAMPLES - 1);
  const float wave_number = FF_TWO_PI / FF_K_WAVELENGTH;
  for (int j = 0; j < FF_SWIM_SAMPLES; ++j) {
    const float x = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)j;
    const float xi = (x_snout - x) / FF_SWIM_EXTENT;
    const float envelope = FF_K_ENVELOPE0 + xi * (FF_K_ENVELOPE1 + xi * FF_K_ENVELOPE2);
    const float envelope_slope = FF_K_ENVELOPE1 + 2.0f * xi * FF_K_ENVELOPE2;
    const float psi = wave_number * xi - FF_TWO_PI * phase;
    const float dh_dxi = scale * (envelope_slope * sin(psi) + envelope * wave_number * cos(psi));
    theta[j] = atan(-dh_dxi / FF_SWIM_EXTENT) + curvature * x;
  }
  /* Every segment clear of folding (METHOD.md section 6). */
  uint limited_here = 0;
  for (int j = 0; j + 1 < FF_SWIM_SAMPLES; ++j) {
    const float bend = (theta[j + 1] - theta[j]) / FF_SWIM_SPACING;
    const float allowed = bend > 0.0f ? swim_max_positive[j] : -swim_max_negative[j];
    if (fabs(bend) <= fabs(allowed)) continue;
    const float shift = (allowed - bend) * FF_SWIM_SPACING;
    for (int after = j + 1; after < FF_SWIM_SAMPLES; ++after) theta[after] += shift;
    ++limited_here;
  }
  limited[i] = limited_here;
  __global float* row = params + i * FF_SWIM_VALUES;
  for (int j = 0; j < FF_SWIM_SAMPLES; ++j) row[FF_SWIM_WAVE + j] = theta[j];
#if FF_SWIM_TAIL >= 0
  row[FF_SWIM_TAIL] =
      FF_K_CAUDAL_AMPLITUDE * scale * cos(FF_TWO_PI * (FF_K_PEDUNCLE / FF_K_WAVELENGTH - phase));
#endif
  const float fin_amplitude =
      FF_K_PECTORAL_AMPLITUDE * clamp(1.0f - body_lengths / FF_K_PECTORAL_HOVER_SPEED, 0.0f, 1.0f);
  const float beat = fin_amplitude * sin(FF_TWO_PI * fin_phase);
#if FF_SWIM_RIGHT >= 0
  row[FF_SWIM_RIGHT] = FF_K_PECTORAL_REST + beat;
#endif
#if FF_SWIM_LEFT >= 0
  row[FF_SWIM_LEFT] = FF_K_PECTORAL_REST - beat;
#endif

  /* Placement (common/placement.cl): the columns of L Q with Q = R_y(yaw) R_z(pitch),
   * the position, 1 / L. */
  const float cy = cos(in[3]), sy = sin(in[3]), cp = cos(in[4]), sp = sin(in[4]);
  const float q[9] = {cy * cp, -cy * sp, sy, sp, cp, 0.0f, -sy * cp, sy * sp, cy}; /* rows */
  __global float* record = placements + i * 16;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) record[3 * c + r] = length * q[3 * r + c];
  }
  record[9] = in[0];
  record[10] = in[1];
  record[11] = in[2];
  record[12] = 1.0f / length;
}

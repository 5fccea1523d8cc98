/* The swim driver (finflex/cl_swim.hpp): FF_SWIM_ITEMS work-items per fish advance its
 * phases by its tail-beat frequency times dt and write its swim rig's parameters (the
 * spine's angles, the fin angles) and its world placement record, as SwimReference
 * does in double precision (engine/src/swim/kinematics.cpp has the formulas and their
 * sources). FF_SWIM_ITEMS is 1 (a work-group's fish side by side) or a power of two up
 * to 64, a work-group of FF_SWIM_GROUP_SIZE = FF_SWIM_ITEMS per fish (the spine's
 * samples shared out, FF_SWIM_CHUNK each; engine/src/device_profile.hpp chooses).
 * Generated before this file (engine/src/swim/cl_swim_driver.cpp):
 *   FF_SWIM_GROUP_SIZE, FF_SWIM_ITEMS, FF_SWIM_SAMPLES, FF_SWIM_VALUES (values per instance),
 *   FF_SWIM_WAVE, FF_SWIM_TAIL, FF_SWIM_RIGHT, FF_SWIM_LEFT (offsets in a row; -1: not
 *   driven), FF_SWIM_X_FIRST, FF_SWIM_SPACING, FF_SWIM_EXTENT, the kinematics FF_K_* and
 *   the per-segment bend limits swim_max_positive[] and swim_max_negative[].
 *
 * inputs:   7 floats per fish: position (3), yaw, pitch, speed, turn rate (SwimInput)
 * sizes:    2 floats per fish: its length (m) and the size term of its tail-beat
 *           frequency (Hz), computed on the host (a cube root)
 * phases:   2 floats per fish, read and written: the wave's and the pectoral fins'
 * params:   FF_SWIM_VALUES floats per fish (slots not driven keep their values)
 * placements: 16 floats per fish (kernels/common/placement.cl's record)
 * limited:  per fish, the spine segments bent less than asked (to clear folding)
 * derived:  with FF_SWIM_DERIVED, FF_SWIM_DERIVED_COUNT floats per fish: the spine's
 *           records (ClSwimDriver::derived_buffer), so the frame needs no rig_prepare */
#define FF_TWO_PI 6.28318530717958647692f
#define FF_SWIM_CHUNK ((FF_SWIM_SAMPLES + FF_SWIM_ITEMS - 1) / FF_SWIM_ITEMS)

inline float swim_wrapped(float phase) { return phase - floor(phase); }

/* The spine's angle at sample j: the travelling wave's slope and the turning bend.
 * The wave's phase psi = 2 pi (xi / wavelength - phase) is taken in turns, its sine and
 * cosine and the arctangent without calls (common/trig.cl). */
FF_INLINE float swim_wave_angle(int j, float phase, float scale, float curvature) {
  const float x = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)j;
  const float x_snout = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)(FF_SWIM_SAMPLES - 1);
  const float wave_number = FF_TWO_PI / FF_K_WAVELENGTH;
  const float xi = (x_snout - x) / FF_SWIM_EXTENT;
  const float envelope = FF_K_ENVELOPE0 + xi * (FF_K_ENVELOPE1 + xi * FF_K_ENVELOPE2);
  const float envelope_slope = FF_K_ENVELOPE1 + 2.0f * xi * FF_K_ENVELOPE2;
  float sin_psi, cos_psi;
  sin_cos_turns(xi / FF_K_WAVELENGTH - phase, &sin_psi, &cos_psi);
  const float dh_dxi = scale * (envelope_slope * sin_psi + envelope * wave_number * cos_psi);
  return arctan(-dh_dxi / FF_SWIM_EXTENT) + curvature * x;
}

__kernel __attribute__((reqd_work_group_size(FF_SWIM_GROUP_SIZE, 1, 1))) void swim_drive(
    __global const float* restrict inputs, __global const float* restrict sizes,
    __global float* restrict phases, __global float* restrict params,
    __global float* restrict placements, __global uint* restrict limited,
    __global float* restrict derived, const float dt, const uint fish) {
  __local float scans[FF_SWIM_GROUP_SIZE / FF_SWIM_ITEMS * (2 * FF_SWIM_ITEMS + 2)];
  const size_t i = get_global_id(0) / FF_SWIM_ITEMS;
  const int item = (int)(get_local_id(0) % FF_SWIM_ITEMS);
  /* Past the last fish: a whole fish's work-items (a whole group when it has more than
   * one, so no barrier is left waiting). */
  if (i >= fish) return;
  __local float* scan = scans + get_local_id(0) / FF_SWIM_ITEMS * (2 * FF_SWIM_ITEMS + 2);
  __global const float* in = inputs + i * 7;
  const float length = sizes[2 * i];
  const float speed = in[5];
  const float body_lengths = speed / length;
  /* Tail-beat frequency (Webb, Kostecki & Stevens 1984): the size term from the host,
   * the speed term; phases integrate it. */
  const float frequency = sizes[2 * i + 1] + FF_K_FREQUENCY_SPEED * body_lengths;
  const float phase = swim_wrapped(phases[2 * i] + frequency * dt);
  const float fin_phase = swim_wrapped(phases[2 * i + 1] + frequency * dt);
  const float scale =
      clamp(FF_K_AMPLITUDE_BASE + FF_K_AMPLITUDE_SPEED * body_lengths, FF_K_AMPLITUDE_MIN, 1.0f);
  const float curvature = clamp(-in[6] * length / fmax(speed, FF_K_MIN_TURN_SPEED),
                                -FF_K_MAX_TURN_CURVATURE, FF_K_MAX_TURN_CURVATURE);

  /* This work-item's samples, and every segment from them cleared of folding (METHOD.md
   * section 6): a segment bent more than allowed turns the samples after it by the
   * difference, which leaves later segments' bends as they were, so each segment is
   * cleared on its own and the turns add up (a scan over the group). Each angle is
   * written with the turns of this work-item's segments before it, then (more than one
   * work-item per fish) those of the samples before this work-item's added. No private
   * arrays and no branches: on 2 CPU cores with PoCL the driver took 0.79 ms a frame for
   * 1,000 fish with them, 0.45 without (its vectoriser still leaves the loop scalar). */
  const int first = min(item * FF_SWIM_CHUNK, FF_SWIM_SAMPLES);
  const int end = min(first + FF_SWIM_CHUNK, FF_SWIM_SAMPLES);
  __global float* row = params + i * FF_SWIM_VALUES;
  float shift = 0.0f, limited_here = 0.0f;
  float here = first < end ? swim_wave_angle(first, phase, scale, curvature) : 0.0f;
  for (int j = first; j < end; ++j) {
    row[FF_SWIM_WAVE + j] = here + shift;
    /* Segment j, from sample j to j + 1 (none after the last sample). */
    const int segment = min(j, FF_SWIM_SAMPLES - 2);
    const float next = swim_wave_angle(segment + 1, phase, scale, curvature);
    const float bend = (next - here) / FF_SWIM_SPACING;
    const float allowed =
        bend > 0.0f ? swim_max_positive[segment] : -swim_max_negative[segment];
    const int over = j + 1 < FF_SWIM_SAMPLES && fabs(bend) > fabs(allowed);
    shift += over ? (allowed - bend) * FF_SWIM_SPACING : 0.0f;
    limited_here += over ? 1.0f : 0.0f;
    here = next;
  }
  /* The turns and limited segments of the samples before this work-item's
   * (common/scan.cl), and in all. */
  const float2 sums = inclusive_scan2((float2)(shift, limited_here), scan, item, FF_SWIM_ITEMS);
  /* The last work-item's sum: in scratch when the fish has more than one. */
  const float limited_total = FF_SWIM_ITEMS == 1 ? sums.y : scan[2 * FF_SWIM_ITEMS - 1];
#if FF_SWIM_ITEMS > 1
  const float shift_before = sums.x - shift;
  for (int j = first; j < end; ++j) row[FF_SWIM_WAVE + j] += shift_before;
#endif
#if FF_SWIM_DERIVED
  /* The spine's records of this frame, as rig_prepare would write them from the row
   * (deformers/spine.cl), once every work-item's angles are in it. */
#if FF_SWIM_ITEMS > 1
  barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
#endif
  spine_records(row + FF_SWIM_WAVE, derived + i * FF_SWIM_DERIVED_COUNT, FF_SWIM_SPINE_X_FIRST,
                FF_SWIM_SPINE_INVERSE_H, FF_SWIM_SPINE_H, FF_SWIM_SAMPLES, scan, item);
#endif
  if (item != 0) return;
  /* The rest is the fish's, once: every work-item read the old phases before the scan's
   * barriers. */
  phases[2 * i] = phase;
  phases[2 * i + 1] = fin_phase;
  limited[i] = (uint)limited_total;
#if FF_SWIM_TAIL >= 0
  float sin_tail, cos_tail;
  sin_cos_turns(FF_K_PEDUNCLE / FF_K_WAVELENGTH - phase, &sin_tail, &cos_tail);
  row[FF_SWIM_TAIL] = FF_K_CAUDAL_AMPLITUDE * scale * cos_tail;
#endif
  const float fin_amplitude =
      FF_K_PECTORAL_AMPLITUDE * clamp(1.0f - body_lengths / FF_K_PECTORAL_HOVER_SPEED, 0.0f, 1.0f);
  float sin_fin, cos_fin;
  sin_cos_turns(fin_phase, &sin_fin, &cos_fin);
  const float beat = fin_amplitude * sin_fin;
#if FF_SWIM_RIGHT >= 0
  row[FF_SWIM_RIGHT] = FF_K_PECTORAL_REST + beat;
#endif
#if FF_SWIM_LEFT >= 0
  row[FF_SWIM_LEFT] = FF_K_PECTORAL_REST - beat;
#endif

  /* Placement (common/placement.cl): the columns of L Q with Q = R_y(yaw) R_z(pitch),
   * the position, 1 / L. */
  float sy, cy, sp, cp;
  sin_cos_radians(in[3], &sy, &cy);
  sin_cos_radians(in[4], &sp, &cp);
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

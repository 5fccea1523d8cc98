/* The swim driver (finflex/cl_swim.hpp): FF_SWIM_ITEMS work-items per fish advance its
 * phases by its tail-beat frequency times dt and write its swim rig's parameters (the
 * spine's angles, the fin angles) and its world placement record, as SwimReference
 * does in double precision (engine/src/swim/kinematics.cpp has the formulas and their
 * sources). FF_SWIM_ITEMS is 1 (a work-group's fish side by side) or a power of two up
 * to 64, a work-group of FF_SWIM_GROUP_SIZE = FF_SWIM_ITEMS per fish (the spine's
 * samples shared out, FF_SWIM_CHUNK each; engine/src/cl/device_profile.hpp chooses); with
 * one work-item per fish, a program of FF_LANES > 1 (CPUs) takes FF_LANES fish per
 * work-item, one in each lane (common/lanes.cl), so the driver is vector code there.
 * Generated before this file (engine/src/swim/cl_driver.cpp):
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

FF_INLINE LaneFloat swim_wrapped(LaneFloat phase) { return phase - floor(phase); }

/* The spine's angle at sample j: the travelling wave's slope and the turning bend.
 * The wave's phase psi = 2 pi (xi / wavelength - phase) is taken in turns, its sine and
 * cosine and the arctangent without calls (common/trig.cl). */
FF_INLINE LaneFloat swim_wave_angle(int j, LaneFloat phase, LaneFloat scale,
                                    LaneFloat curvature) {
  const float x = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)j;
  const float x_snout = FF_SWIM_X_FIRST + FF_SWIM_SPACING * (float)(FF_SWIM_SAMPLES - 1);
  const float wave_number = FF_TWO_PI / FF_K_WAVELENGTH;
  const float xi = (x_snout - x) / FF_SWIM_EXTENT;
  const float envelope = FF_K_ENVELOPE0 + xi * (FF_K_ENVELOPE1 + xi * FF_K_ENVELOPE2);
  const float envelope_slope = FF_K_ENVELOPE1 + 2.0f * xi * FF_K_ENVELOPE2;
  LaneFloat sin_psi, cos_psi;
  sin_cos_turns(xi / FF_K_WAVELENGTH - phase, &sin_psi, &cos_psi);
  const LaneFloat dh_dxi = scale * (envelope_slope * sin_psi + envelope * wave_number * cos_psi);
  return arctan(-dh_dxi / FF_SWIM_EXTENT) + curvature * x;
}

__kernel __attribute__((reqd_work_group_size(FF_SWIM_GROUP_SIZE, 1, 1))) void swim_drive(
    __global const float* restrict inputs, __global const float* restrict sizes,
    __global float* restrict phases, __global float* restrict params,
    __global float* restrict placements, __global uint* restrict limited,
    __global float* restrict derived, const float dt, const uint fish) {
#if FF_LANES == 1
  __local float scans[FF_SWIM_GROUP_SIZE / FF_SWIM_ITEMS * (2 * FF_SWIM_ITEMS + 2)];
  const size_t i = get_global_id(0) / FF_SWIM_ITEMS;
  const int item = (int)(get_local_id(0) % FF_SWIM_ITEMS);
  /* Past the last fish: a whole fish's work-items (a whole group when it has more than
   * one, so no barrier is left waiting). */
  if (i >= fish) return;
  __local float* scan = scans + get_local_id(0) / FF_SWIM_ITEMS * (2 * FF_SWIM_ITEMS + 2);
  const int at = (int)i; /* the fish */
#else
  /* FF_LANES fish, one per lane; lanes past the last fish repeat it: the same inputs
   * give the same values, stored after its own lane's to the same places. */
  if (get_global_id(0) * FF_LANES >= fish) return;
  const int item = 0;
  __local float* scan = 0;
  const LaneInt at = min((int)(get_global_id(0) * FF_LANES) + FF_LANE_IDS, (int)fish - 1);
#endif
  const LaneInt in = 7 * at; /* the fish's SwimInput */
  const LaneFloat length = FF_GATHER(sizes, 2 * at);
  const LaneFloat speed = FF_GATHER(inputs, in + 5);
  const LaneFloat body_lengths = speed / length;
  /* Tail-beat frequency (Webb, Kostecki & Stevens 1984): the size term from the host,
   * the speed term; phases integrate it. */
  const LaneFloat frequency = FF_GATHER(sizes, 2 * at + 1) + FF_K_FREQUENCY_SPEED * body_lengths;
  const LaneFloat phase = swim_wrapped(FF_GATHER(phases, 2 * at) + frequency * dt);
  const LaneFloat fin_phase = swim_wrapped(FF_GATHER(phases, 2 * at + 1) + frequency * dt);
  const LaneFloat scale =
      clamp(FF_K_AMPLITUDE_BASE + FF_K_AMPLITUDE_SPEED * body_lengths, FF_K_AMPLITUDE_MIN, 1.0f);
  const LaneFloat curvature = clamp(-FF_GATHER(inputs, in + 6) * length /
                                        fmax(speed, FF_K_MIN_TURN_SPEED),
                                    -FF_K_MAX_TURN_CURVATURE, FF_K_MAX_TURN_CURVATURE);

  /* This work-item's samples, and every segment from them cleared of folding (METHOD.md
   * section 6): a segment bent more than allowed turns the samples after it by the
   * difference, which leaves later segments' bends as they were, so each segment is
   * cleared on its own and the turns add up (a scan over the group). Each angle is
   * written with the turns of this work-item's segments before it, then (more than one
   * work-item per fish) those of the samples before this work-item's added. No private
   * arrays and no branches: on 2 CPU cores with PoCL the driver took 0.79 ms a frame for
   * 1,000 fish with them, 0.45 without, when it was one lane (its vectoriser still left
   * the loop scalar). */
  const int first = min(item * FF_SWIM_CHUNK, FF_SWIM_SAMPLES);
  const int end = min(first + FF_SWIM_CHUNK, FF_SWIM_SAMPLES);
  const LaneInt row = FF_SWIM_VALUES * at; /* the fish's parameters */
  LaneFloat shift = 0.0f, limited_here = 0.0f;
  LaneFloat here = first < end ? swim_wave_angle(first, phase, scale, curvature) : 0.0f;
  for (int j = first; j < end; ++j) {
    lanes_scatter(params, row + (FF_SWIM_WAVE + j), here + shift);
    /* Segment j, from sample j to j + 1 (none after the last sample). */
    const int segment = min(j, FF_SWIM_SAMPLES - 2);
    const LaneFloat next = swim_wave_angle(segment + 1, phase, scale, curvature);
    const LaneFloat bend = (next - here) / FF_SWIM_SPACING;
    const LaneFloat allowed = bend > 0.0f ? (LaneFloat)swim_max_positive[segment]
                                          : (LaneFloat)(-swim_max_negative[segment]);
    const LaneMask over =
        FF_UNIFORM_MASK(j + 1 < FF_SWIM_SAMPLES) & (fabs(bend) > fabs(allowed));
    shift += over ? (allowed - bend) * FF_SWIM_SPACING : (LaneFloat)0.0f;
    limited_here += over ? (LaneFloat)1.0f : (LaneFloat)0.0f;
    here = next;
  }
#if FF_SWIM_ITEMS > 1
  /* The turns and limited segments of the samples before this work-item's
   * (common/scan.cl), and in all (the last work-item's sum, in scratch). */
  const float2 sums = inclusive_scan2((float2)(shift, limited_here), scan, item, FF_SWIM_ITEMS);
  const float limited_total = scan[2 * FF_SWIM_ITEMS - 1];
  const float shift_before = sums.x - shift;
  for (int j = first; j < end; ++j) params[row + FF_SWIM_WAVE + j] += shift_before;
#else
  const LaneFloat limited_total = limited_here;
#endif
#if FF_SWIM_DERIVED
  /* The spine's records of this frame, as rig_prepare would write them from the row
   * (deformers/spine.cl), once every work-item's angles are in it. */
#if FF_SWIM_ITEMS > 1
  barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
#endif
  spine_records(params, row + FF_SWIM_WAVE, derived, FF_SWIM_DERIVED_COUNT * at,
                FF_SWIM_SPINE_X_FIRST, FF_SWIM_SPINE_INVERSE_H, FF_SWIM_SPINE_H, FF_SWIM_SAMPLES,
                scan, item);
#endif
  if (item != 0) return;
  /* The rest is the fish's, once: every work-item read the old phases before the scan's
   * barriers. */
  lanes_scatter(phases, 2 * at, phase);
  lanes_scatter(phases, 2 * at + 1, fin_phase);
  lanes_scatter_count(limited, at, limited_total);
#if FF_SWIM_TAIL >= 0
  LaneFloat sin_tail, cos_tail;
  sin_cos_turns(FF_K_PEDUNCLE / FF_K_WAVELENGTH - phase, &sin_tail, &cos_tail);
  lanes_scatter(params, row + FF_SWIM_TAIL, FF_K_CAUDAL_AMPLITUDE * scale * cos_tail);
#endif
  const LaneFloat fin_amplitude =
      FF_K_PECTORAL_AMPLITUDE * clamp(1.0f - body_lengths / FF_K_PECTORAL_HOVER_SPEED, 0.0f, 1.0f);
  LaneFloat sin_fin, cos_fin;
  sin_cos_turns(fin_phase, &sin_fin, &cos_fin);
  const LaneFloat beat = fin_amplitude * sin_fin;
#if FF_SWIM_RIGHT >= 0
  lanes_scatter(params, row + FF_SWIM_RIGHT, FF_K_PECTORAL_REST + beat);
#endif
#if FF_SWIM_LEFT >= 0
  lanes_scatter(params, row + FF_SWIM_LEFT, FF_K_PECTORAL_REST - beat);
#endif

  /* Placement (common/placement.cl): the columns of L Q with Q = R_y(yaw) R_z(pitch),
   * the position, 1 / L. */
  LaneFloat sy, cy, sp, cp;
  sin_cos_radians(FF_GATHER(inputs, in + 3), &sy, &cy);
  sin_cos_radians(FF_GATHER(inputs, in + 4), &sp, &cp);
  const LaneFloat q[9] = {cy * cp,  -cy * sp, sy,      sp, cp, (LaneFloat)0.0f,
                          -sy * cp, sy * sp,  cy}; /* rows */
  const LaneInt record = 16 * at;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r)
      lanes_scatter(placements, record + (3 * c + r), length * q[3 * r + c]);
  }
  for (int c = 0; c < 3; ++c)
    lanes_scatter(placements, record + (9 + c), FF_GATHER(inputs, in + c));
  lanes_scatter(placements, record + 12, 1.0f / length);
}

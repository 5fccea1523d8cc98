/* The general inextensible spine (METHOD.md section 6): per instance a table of
 * tangent angles theta_k at `samples` points x_k evenly spaced over the stage's extent
 * in x, theta linear in between and constant beyond the ends. The spine is
 *   X(x) = integral_0^x cos theta,  Z(x) = integral_0^x sin theta,
 * so it keeps its arc length exactly at any angle, x = 0 (the pivot) staying fixed;
 * n = (-sin theta, 0, cos theta), curvature k = theta'(x). The paper's bend is the case
 * theta = asin(2 m x). Registry entry: engine/src/rig/deformers/spine.cpp.
 *
 * Over one segment, with theta linear (slope a) from theta_j, the integrals are closed
 * forms: integral_0^d cos(theta_j + a t) dt = d cos(theta_j + a d / 2) sinc(a d / 2),
 * and the same with sin (sinc(u) = sin(u) / u). The running integrals at the samples,
 * X_k and Z_k (from x = 0), are the stage's derived values, written by spine_prepare
 * once per instance and frame: a vertex then integrates only its own segment.
 *
 * Stage table constants (DeformerType::stage_constants): 0 x_0 (the first sample),
 * 1 1 / h, 2 h (the spacing), 3 samples - 1. Derived values: a record of 8 floats per
 * sample k, (X_k, Z_k, sin theta_k, cos theta_k, the slope a of theta over segment k,
 * theta_k, a / 2, x_k = x_0 + k h), 32-byte aligned: everything a vertex in segment k
 * needs in one memory sector, read on GPUs as two 4-vectors. The half slope and x_k
 * are stored so that a vertex takes its half turn a d / 2 and (within the table) its
 * distance d from x_k in one operation each. */

/* Lane kernels: the most segments whose records a work-item's lanes blend instead of
 * gathering them. */
#define FF_SPINE_BLEND 4

/* Trigonometry from kernels/common/trig.cl (no calls: the kernel vectorises). Angles
 * stay within [-pi, pi] (the values' limit); half a segment's turn within pi/2, where
 * sin_over_h holds, as long as no segment turns by more than pi; within
 * FF_GENTLE_HALF_TURN, where the shorter sin_over_h_gentle holds, for segments that turn
 * by at most 0.5 rad (a swimming fish's turn by a few hundredths). */

/* The spine at a vertex at x and height z, `position` its x in samples from the first
 * (x - x_0) / h: derived (the angles' records); ascending: the lanes hold ascending x
 * (vertices straight from the rest planes, spine_stage_from_rest), so their segments
 * range from the first lane's to the last's; within_table: every lane lies within the
 * table (0 <= position <= samples - 1), none beyond its ends (spine_sample knows it for
 * ascending lanes from the first and the last).
 * Within a segment theta = theta_j + 2 delta at the vertex, delta = half the turn so
 * far: the chord to the vertex has length d sinc(delta) along theta_j + delta. The
 * sines and cosines at the middle and at the end come from those of theta_j (the
 * record) and of delta (short series) by the angle-addition formulas; with
 * FF_NATIVE_TRIG (engine/src/cl/device_profile.hpp: NVIDIA's GPUs) from the hardware's
 * sine and cosine of the two angles instead, fewer instructions on the arithmetic
 * units. */
FF_INLINE SecantSample spine_at(LaneFloat x, LaneFloat position, LaneFloat z,
                                __global const float* derived, StageFrame f, int ascending,
                                int within_table, int known_segments, int first_segment) {
  const float h = FF_STAGE_CONSTANT(f, 2);
  const float last = FF_STAGE_CONSTANT(f, 3);
  /* The segment, floor(position) within [0, last - 1]: the conversion to int of the
   * clamped position, which truncates, the same as floor for values >= 0 (PoCL's
   * floor() takes a dozen instructions, the conversion one). */
  const LaneFloat within =
      within_table ? fmin(position, last - 1.0f) : clamp(position, 0.0f, last - 1.0f);
#if FF_LANES > 1
  /* known_segments (within the table): every lane lies in segment first_segment
   * (spine_lanes_segment: known_segments 1) or in it and the next (spine_stage_swept:
   * 2), known without the position; a lane is in the next one from its first sample on. */
  const LaneInt segment_index = known_segments ? (LaneInt)first_segment : FF_LANE_INT(within);
  const LaneFloat segment = within_table ? (LaneFloat)0.0f : FF_LANE_FLOAT(segment_index);
  /* Each lane's own segment's record. The slots of a spine's component are sorted by x
   * (engine/src/cl/slot_layout.hpp, make_slot_layout), so the lanes of most work-items
   * share one segment, and those of the rest a few neighbouring ones (a fin's vertices
   * reach the spine after their hinge, which moves them a little along it): the
   * records from the lowest lane's segment to the highest's, up to FF_SPINE_BLEND
   * of them, are each read once and taken by the lanes in their segment; a wider
   * spread is gathered lane by lane (common/lanes.cl): five gathers of 16 lanes cost
   * more than reading and blending a few records (the fins' kernel 2.8 -> 2.6 ms a
   * frame for 1,000 fish on 2 cores; blending up to 2, 4 or 8 records, alike). */
  const LaneInt record = 8 * segment_index;
  const int2 known_range = (int2)(8 * first_segment, 8 * (first_segment + known_segments - 1));
  const int2 range = known_segments ? known_range :
                     ascending      ? lanes_ends(record) :
                                      lanes_range(record);
  LaneFloat x_j, z_j, sin_j, cos_j, slope, half_slope, sample_x;
  /* The largest |a / 2| of the records read (blended ones only; gathered: none known). */
  float steepest = INFINITY;
  if (range.y - range.x < 8 * FF_SPINE_BLEND) {
    __global const float* first = derived + range.x;
    x_j = (LaneFloat)first[0];
    z_j = (LaneFloat)first[1];
    sin_j = (LaneFloat)first[2];
    cos_j = (LaneFloat)first[3];
    slope = (LaneFloat)first[4];
    half_slope = (LaneFloat)first[6];
    sample_x = (LaneFloat)first[7];
    steepest = fabs(first[6]);
    for (int k = range.x + 8; k <= range.y; k += 8) {
      __global const float* shared = derived + k;
      const LaneMask here = known_segments ? x >= (LaneFloat)shared[7] : record == (LaneInt)k;
      x_j = here ? (LaneFloat)shared[0] : x_j;
      z_j = here ? (LaneFloat)shared[1] : z_j;
      sin_j = here ? (LaneFloat)shared[2] : sin_j;
      cos_j = here ? (LaneFloat)shared[3] : cos_j;
      slope = here ? (LaneFloat)shared[4] : slope;
      half_slope = here ? (LaneFloat)shared[6] : half_slope;
      sample_x = here ? (LaneFloat)shared[7] : sample_x;
      steepest = fmax(steepest, fabs(shared[6]));
    }
  } else {
    x_j = FF_GATHER(derived, record);
    z_j = FF_GATHER(derived + 1, record);
    sin_j = FF_GATHER(derived + 2, record);
    cos_j = FF_GATHER(derived + 3, record);
    slope = FF_GATHER(derived + 4, record);
    half_slope = FF_GATHER(derived + 6, record);
    sample_x = FF_GATHER(derived + 7, record);
  }
#else
  const int segment_index = (int)within;
  const float segment = (float)segment_index;
  __global const float* record = derived + 8 * segment_index;
#if FF_GPU
  const float4 at_j = *(__global const float4*)record; /* aligned: two loads */
  const float4 more_j = *(__global const float4*)(record + 4);
  const float x_j = at_j.x, z_j = at_j.y, sin_j = at_j.z, cos_j = at_j.w;
  const float slope = more_j.x, theta_j = more_j.y, half_slope = more_j.z;
#else
  const float x_j = record[0], z_j = record[1], sin_j = record[2], cos_j = record[3];
  const float slope = record[4], theta_j = record[5], half_slope = record[6];
#endif
  const float sample_x = 0.0f; /* one lane: within_table is 0 */
#endif
  /* d from x_k (outside the table: < 0 or > h); inside, the part of d where theta is
   * linear; beyond, the rest (beyond the ends theta is constant). Written out for
   * within_table, where beyond is 0: the compiler may not drop a product with 0.
   * Within the table d = x - x_k (the record's x_k), one operation; elsewhere from the
   * position, as the segment was chosen, so that d >= 0 wherever the position is:
   * x - x_k may round below 0 at a sample, which would take the vertex for one beyond
   * the table's end (no curvature). */
  const LaneFloat d = within_table ? x - sample_x : (position - segment) * h;
  const LaneFloat inside = within_table ? d : clamp(d, 0.0f, h);
  const LaneFloat beyond = within_table ? (LaneFloat)0.0f : d - inside;
  const LaneFloat delta = half_slope * inside;
  /* |delta| <= |a / 2| h, inside being at most h: the short polynomials where every lane's
   * segment turns gently (common/trig.cl), on CPUs, where the work-item's lanes take one
   * branch (a work-item of one lane would branch apart from its warp's neighbours). */
#if FF_LANES > 1
  const int gentle = steepest * h <= FF_GENTLE_HALF_TURN;
#else
  const int gentle = 0;
#endif
  LaneFloat sinc_delta, cos_delta;
  sinc_and_cos(delta, gentle, &sinc_delta, &cos_delta);
  /* theta_j + delta (the chord's direction) and theta_j + 2 delta (the end). */
#if FF_NATIVE_TRIG && FF_LANES == 1
  const float mid = theta_j + delta, end = mid + delta; /* within [-pi, pi] */
  const float sin_mid = native_sin(mid), cos_mid = native_cos(mid);
  const float sin_end = native_sin(end), cos_end = native_cos(end);
#else
  const LaneFloat sin_delta = delta * sinc_delta;
  const LaneFloat sin_mid = sin_j * cos_delta + cos_j * sin_delta;
  const LaneFloat cos_mid = cos_j * cos_delta - sin_j * sin_delta;
  /* The end: the middle turned by delta again. */
  const LaneFloat sin_end = sin_mid * cos_delta + cos_mid * sin_delta;
  const LaneFloat cos_end = cos_mid * cos_delta - sin_mid * sin_delta;
#endif
  const LaneFloat chord = inside * sinc_delta;
  SecantSample s;
  s.spine_x = x_j + chord * cos_mid;
  s.spine_z = z_j + chord * sin_mid;
  if (!within_table) {
    s.spine_x += beyond * cos_end;
    s.spine_z += beyond * sin_end;
  }
  s.sin_t = sin_end;
  s.cos_t = cos_end;
  /* |df/dx| = 1; k = slope within the table, 0 beyond it (METHOD.md section 6). */
  s.along = 1.0f;
  s.across = 1.0f - z * (beyond == 0.0f ? slope : (LaneFloat)0.0f);
  return s;
}

/* The one segment all the work-item's lanes lie in, or -1 where they span more than one
 * or reach beyond the table, for lanes straight from the rest planes: the rig program
 * finds it once (engine/src/cl/segment_tables.cpp slot_segments, the generated
 * ff_slot_segments, an entry per 8 rest slots: the segment of its first slot in bits
 * 0-11, as the position below gives it, and bits 12, 13 and 14 set where the 8, 16 or
 * 32 slots from it all lie in that segment), so a frame does not: a sixth of the fused
 * kernel's arithmetic on PoCL 3.1. One load: reading an entry for each 8 lanes and
 * combining them gave that sixth back (docs/benchmarks.md, Swimming, "segment"). */
#if FF_LANES > 1
/* The bit of an entry set where the work-item's FF_LANES slots share its segment. */
#define FF_SHARED_SEGMENT_BIT (1u << (FF_LANES == 32 ? 14 : FF_LANES == 16 ? 13 : 12))

FF_INLINE int spine_lanes_segment(void) {
#ifdef FF_SLOT_SEGMENTS
  const uint entry = ff_slot_segments[FF_FIRST_SLOT / 8];
  return (entry & FF_SHARED_SEGMENT_BIT) != 0u ? (int)(entry & 0xfffu) : -1;
#else
  return -1;
#endif
}
#endif

/* The spine at x of a vertex at height z (spine_at), a branch per work-item: ascending
 * lanes all within the table leave out what beyond it costs, and those in one known
 * segment what finding it costs. */
FF_INLINE SecantSample spine_sample(LaneFloat x, LaneFloat z, __global const float* derived,
                                    StageFrame f, int ascending) {
#if FF_LANES > 1
  if (ascending) {
    const int lanes_segment = spine_lanes_segment();
    /* The position goes unused there: x stands in for it. */
    if (lanes_segment >= 0) return spine_at(x, x, z, derived, f, 1, 1, 1, lanes_segment);
  }
#endif
  /* x - x_0 first (exact near x_0), so that the sign of the position is x's against the
   * table's first sample: a multiply-add x / h - x_0 / h rounds some x just below x_0
   * to 0 and takes them into the table, where the curvature is not 0. */
  const LaneFloat position = (x - FF_STAGE_CONSTANT(f, 0)) * FF_STAGE_CONSTANT(f, 1);
#if FF_LANES > 1
  if (ascending && FF_FIRST_LANE(position) >= 0.0f &&
      FF_LAST_LANE(position) <= FF_STAGE_CONSTANT(f, 3)) {
    return spine_at(x, position, z, derived, f, 1, 1, 0, 0);
  }
#endif
  return spine_at(x, position, z, derived, f, ascending, 0, 0, 0);
}

/* Stage functions (kernels/common/stage_frame.cl): the angles' records (derived). The
 * second for vertices straight from the rest planes, whose slots are sorted by x in the
 * spine's frame (DeformerType::cl_rest_function): a work-item's lanes hold ascending x. */
FF_INLINE SecantSample spine_stage(Vec3 p, StageFrame f, __global const float* values,
                                   __global const float* derived) {
  return spine_sample(p.x, p.z, derived, f, 0);
}

FF_INLINE SecantSample spine_stage_from_rest(Vec3 p, StageFrame f, __global const float* values,
                                             __global const float* derived) {
  return spine_sample(p.x, p.z, derived, f, 1);
}

/* Stage function (DeformerType::cl_swept_function) for vertices that reach the spine
 * after one stage of one value, `moved_by`, moved them along it (a fin's hinge): the
 * rig program found, per 8 slots and bin of that value's range [-limit, limit], the two
 * neighbouring segments they stay in for every value in the bin, where they do
 * (engine/src/cl/segment_tables.cpp swept_segments, the generated ff_swept_segments: the
 * first of the two, and bits as ff_slot_segments'). Where all the work-item's lanes do,
 * it takes them without finding them (most of a swimming fish's fin work-items). */
FF_INLINE SecantSample spine_stage_swept(Vec3 p, StageFrame f, __global const float* values,
                                         __global const float* derived, float moved_by,
                                         int first_entry, float limit, float bins_per_unit) {
#if FF_LANES > 1 && defined(FF_SWEPT_SEGMENTS)
  const float bin = (moved_by + limit) * bins_per_unit;
  if (bin >= 0.0f && bin < (float)FF_SWEPT_BINS) {
    const uint entry =
        ff_swept_segments[first_entry + (int)(FF_FIRST_SLOT / 8) * FF_SWEPT_BINS + (int)bin];
    /* The position goes unused there: x stands in for it. */
    if ((entry & FF_SHARED_SEGMENT_BIT) != 0u) {
      return spine_at(p.x, p.x, p.z, derived, f, 0, 1, 2, (int)(entry & 0xfffu));
    }
  }
#endif
  return spine_sample(p.x, p.z, derived, f, 0);
}

/* The records of one instance's angles (rig_prepare, one-lane programs; each of the
 * instance's FF_PREPARE_ITEMS work-items calls it, `item` its place), or of each lane's
 * instance (the swim driver's fish on CPUs, one work-item per FF_LANES fish): the
 * running integrals X_k, Z_k from x = 0, sin theta_k, cos theta_k, and the segment's
 * slope. theta_k is theta_rows[theta_at + k] and record k starts at
 * derived_rows[derived_at + 8 k], lane by lane.
 * Work-item i takes the samples [i c, (i + 1) c), c = ceil(samples / FF_PREPARE_ITEMS)
 * <= FF_SPINE_CHUNK (samples are at most FF_SPINE_MAX_SAMPLES: 256, spine.cpp, unless
 * the program knows its table): it sums the chords of its segments, a scan over the
 * instance's work-items (common/scan.cl, in scratch) gives each chunk the integral
 * before it, the work-item holding x = 0 publishes the integral there, and every
 * record is written once, from x = 0. */
/* (An instance per lane takes one work-item per instance: a program of more than one
 * lane with more work-items per instance, which only deforms, has none of this.) */
#if defined(FF_PREPARE_ITEMS) && (FF_LANES == 1 || FF_PREPARE_ITEMS == 1)
#ifndef FF_SPINE_MAX_SAMPLES
#define FF_SPINE_MAX_SAMPLES 256
#endif
#define FF_SPINE_CHUNK ((FF_SPINE_MAX_SAMPLES + FF_PREPARE_ITEMS - 1) / FF_PREPARE_ITEMS)

/* The chord of the segment from theta_k to theta_next (theta linear over it): length
 * h sinc(turn/2) along theta_k + turn / 2. */
FF_INLINE void spine_chord(LaneFloat theta_k, LaneFloat theta_next, float h, LaneFloat* x,
                           LaneFloat* z) {
  const LaneFloat half_turn = 0.5f * (theta_next - theta_k);
  LaneFloat sin_mid, cos_mid;
  sin_cos(theta_k + half_turn, &sin_mid, &cos_mid);
  const LaneFloat length = h * sin_over_h(half_turn);
  *x = length * cos_mid;
  *z = length * sin_mid;
}

/* Record k's 8 floats at rows + at (lane by lane: each lane's 8 floats in one store);
 * sample_x: x_k, the same for every lane. */
#if FF_LANES == 1
FF_INLINE void store_spine_record(__global float* rows, int at, float x, float z, float sin_k,
                                  float cos_k, float slope, float theta_k, float sample_x) {
  __global float* record = rows + at;
  record[0] = x;
  record[1] = z;
  record[2] = sin_k;
  record[3] = cos_k;
  record[4] = slope;
  record[5] = theta_k;
  record[6] = 0.5f * slope;
  record[7] = sample_x;
}
#else
FF_INLINE void store_spine_record(__global float* rows, LaneInt at, LaneFloat x, LaneFloat z,
                                  LaneFloat sin_k, LaneFloat cos_k, LaneFloat slope,
                                  LaneFloat theta_k, float sample_x) {
  for (int lane = 0; lane < FF_LANES; ++lane) {
    const float slope_lane = FF_FLOAT_LANE(slope, lane);
    vstore8((float8)(FF_FLOAT_LANE(x, lane), FF_FLOAT_LANE(z, lane), FF_FLOAT_LANE(sin_k, lane),
                     FF_FLOAT_LANE(cos_k, lane), slope_lane, FF_FLOAT_LANE(theta_k, lane),
                     0.5f * slope_lane, sample_x),
            0, rows + FF_INT_LANE(at, lane));
  }
}
#endif

/* The records from the table's constants (the stage table's, or the same values
 * generated into the swim driver, which writes them in the same frame's kernel:
 * kernels/swim/driver.cl). */
FF_INLINE void spine_records(__global const float* theta_rows, LaneInt theta_at,
                             __global float* derived_rows, LaneInt derived_at, float x_first,
                             float inverse_h, float h, int count, __local float* scratch,
                             int item) {
  const int items = FF_PREPARE_ITEMS;
  const int chunk = (count + items - 1) / items;
  const int first = min(item * chunk, count), end = min(first + chunk, count);
  /* The integrals at this work-item's samples, from its first one. */
  LaneFloat at_x[FF_SPINE_CHUNK], at_z[FF_SPINE_CHUNK];
  LaneFloat sum_x = 0.0f, sum_z = 0.0f;
  for (int k = first; k < end; ++k) {
    at_x[k - first] = sum_x;
    at_z[k - first] = sum_z;
    if (k + 1 < count) {
      LaneFloat chord_x, chord_z;
      spine_chord(FF_GATHER(theta_rows, theta_at + k), FF_GATHER(theta_rows, theta_at + k + 1),
                  h, &chord_x, &chord_z);
      sum_x += chord_x;
      sum_z += chord_z;
    }
  }
  /* The integral before this work-item's first sample (common/scan.cl). */
#if FF_PREPARE_ITEMS > 1
  const float2 through = inclusive_scan2((float2)(sum_x, sum_z), scratch, item, items);
  const float before_x = through.x - sum_x, before_z = through.y - sum_z;
#else
  const float before_x = 0.0f, before_z = 0.0f;
#endif
  /* x = 0 (it may lie outside the table) in segment j; its integral from the first
   * sample, published by the work-item holding sample j. */
  const float position = -x_first * inverse_h;
  const float segment = clamp(floor(position), 0.0f, (float)(count - 2));
  const int j = (int)segment;
  LaneFloat origin_x = 0.0f, origin_z = 0.0f;
  if (j >= first && j < end) {
    const float d = (position - segment) * h;
    const float inside = clamp(d, 0.0f, h);
    const float beyond = d - inside;
    const LaneFloat theta_j = FF_GATHER(theta_rows, theta_at + j);
    const LaneFloat half_turn =
        0.5f * (FF_GATHER(theta_rows, theta_at + j + 1) - theta_j) * inverse_h * inside;
    const LaneFloat chord = inside * sin_over_h(half_turn);
    LaneFloat sin_mid, cos_mid, sin_end, cos_end;
    sin_cos(theta_j + half_turn, &sin_mid, &cos_mid);
    sin_cos(theta_j + 2.0f * half_turn, &sin_end, &cos_end);
    origin_x = before_x + at_x[j - first] + chord * cos_mid + beyond * cos_end;
    origin_z = before_z + at_z[j - first] + chord * sin_mid + beyond * sin_end;
#if FF_PREPARE_ITEMS > 1
    scratch[2 * items] = origin_x;
    scratch[2 * items + 1] = origin_z;
#endif
  }
#if FF_PREPARE_ITEMS > 1
  FF_PREPARE_BARRIER();
  origin_x = scratch[2 * items];
  origin_z = scratch[2 * items + 1];
#endif
  for (int k = first; k < end; ++k) {
    const LaneFloat theta_k = FF_GATHER(theta_rows, theta_at + k);
    LaneFloat sin_k, cos_k;
    sin_cos(theta_k, &sin_k, &cos_k);
    const LaneFloat slope =
        k + 1 < count ? (FF_GATHER(theta_rows, theta_at + k + 1) - theta_k) * inverse_h
                      : (LaneFloat)0.0f;
    store_spine_record(derived_rows, derived_at + 8 * k, before_x + at_x[k - first] - origin_x,
                       before_z + at_z[k - first] - origin_z, sin_k, cos_k, slope, theta_k,
                       x_first + (float)k * h);
  }
}
#endif

#if FF_LANES == 1
FF_INLINE void spine_prepare(__global const float* theta, __global float* derived, StageFrame f,
                             __local float* scratch, int item) {
  spine_records(theta, 0, derived, 0, FF_STAGE_CONSTANT(f, 0), FF_STAGE_CONSTANT(f, 1),
                FF_STAGE_CONSTANT(f, 2), (int)FF_STAGE_CONSTANT(f, 3) + 1, scratch, item);
}
#endif

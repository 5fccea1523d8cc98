/* The level of detail of every instance, each frame, on the device
 * (engine/include/finflex/level_choice.hpp has the contract; its host twin is
 * choose_level_on_host in engine/src/lod/level_choice.cpp). Three kernels, over
 * groups of FF_LOD_GROUP instances:
 *   lod_choose   per instance: culled (-1) unless its bounding sphere meets a view's
 *                frustum where no wall hides it; else the coarsest level whose error, projected at the
 *                sphere's nearest depth in the views that see it, is within the pixel
 *                budget, held where the finer level it had is (hysteresis). Counts
 *                the group's instances per level.
 *   lod_offsets  one group: where each group's instances of each level start among
 *                that level's, each level's count and its indirect draw arguments.
 *   lod_scatter  per instance: its place in its level's list (ascending instance
 *                order: the same frame always gives the same lists).
 * Each level's list has room for rows[k] instances (level_rows: rows, then each list's
 * first entry); level k's sequence is its own instances, then those that found no room
 * in level k - 1's (in that level's sequence order): an instance past the rows of its
 * level is drawn at the next coarser level with room, or not at all (counted).
 * Generated before this file: FF_LOD_GROUP (work-items per group, a power of two) and
 * FF_LOD_LEVELS (1..16).
 *
 * A view (at most 4) is 32 floats (two float16 arguments): 6 frustum planes (a, b, c,
 * d; a point is inside where a x + b y + c z + d >= 0, (a, b, c) of unit length), the
 * view depth row (depth = dot(row.xyz, p) + row.w: the distance in front of the
 * camera), the near plane's depth and the focal length in pixels; its eye is a float4
 * argument of its own (for the walls, lod/wall_occlusion.cl, generated before this
 * file with the rest). A placement record: kernels/common/
 * placement.cl (columns of L Q at 0-8, the position at 9-11, 1 / L at 12). */
#define FF_LOD_INLINE inline __attribute__((always_inline))

/* Whether the sphere (centre c, radius) meets the frustum plane (a, b, c, d). */
FF_LOD_INLINE bool within_plane(const float4 plane, const float3 c, const float radius) {
  return dot(plane.xyz, c) + plane.w >= -radius;
}

/* The size of a body length in pixels in one view (its 32 floats as two
 * float16: a holds planes 0-3, b planes 4-5, the depth row, the near depth and the focal
 * length), or -1 where the sphere misses its frustum or a wall hides it. Straight from the arguments: a
 * copy of the views into a private array spilled to memory on GPUs, and cost more
 * than the choice itself. */
FF_LOD_INLINE float view_pixels(const float16 a, const float16 b, const float4 eye,
                                const float3 c, const float radius, const float length,
                                __global const float4* restrict walls, const uint wall_count) {
  const bool inside = within_plane(a.s0123, c, radius) && within_plane(a.s4567, c, radius) &&
                      within_plane(a.s89ab, c, radius) && within_plane(a.scdef, c, radius) &&
                      within_plane(b.s0123, c, radius) && within_plane(b.s4567, c, radius);
  if (!inside || walls_hide(eye.xyz, c, radius, walls, wall_count)) return -1.0f;
  const float depth = dot(b.s89a, c) + b.sb - radius;
  return length * b.sd / fmax(depth, b.sc);
}

__kernel __attribute__((reqd_work_group_size(FF_LOD_GROUP, 1, 1))) void lod_choose(
    __global const float* restrict placements, const uint instances, const float4 bounds,
    __global const float* restrict level_errors, const float16 view0_a, const float16 view0_b,
    const float16 view1_a, const float16 view1_b, const float16 view2_a, const float16 view2_b,
    const float16 view3_a, const float16 view3_b, const float4 eye0, const float4 eye1,
    const float4 eye2, const float4 eye3, const uint view_count,
    __global const float4* restrict walls, const uint wall_count, const float budget,
    const float keep_budget, __global int* restrict level_of,
    __global uint* restrict group_counts) {
  __local uint counts[FF_LOD_LEVELS];
  const uint item = get_local_id(0);
  if (item < FF_LOD_LEVELS) counts[item] = 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  const size_t i = get_global_id(0);
  if (i < instances) {
    __global const float* r = placements + i * 16;
    /* The sphere in the world: centre position + L Q c, radius L * radius. */
    const float3 centre = (float3)(r[9], r[10], r[11]) + bounds.x * (float3)(r[0], r[1], r[2]) +
                          bounds.y * (float3)(r[3], r[4], r[5]) +
                          bounds.z * (float3)(r[6], r[7], r[8]);
    const float length = 1.0f / r[12];
    const float radius = length * bounds.w;
    /* The largest size of a body length in pixels over the views that see it. */
    float pixels_per_length =
        view_pixels(view0_a, view0_b, eye0, centre, radius, length, walls, wall_count);
    if (view_count > 1) {
      pixels_per_length = fmax(pixels_per_length, view_pixels(view1_a, view1_b, eye1, centre,
                                                              radius, length, walls, wall_count));
    }
    if (view_count > 2) {
      pixels_per_length = fmax(pixels_per_length, view_pixels(view2_a, view2_b, eye2, centre,
                                                              radius, length, walls, wall_count));
    }
    if (view_count > 3) {
      pixels_per_length = fmax(pixels_per_length, view_pixels(view3_a, view3_b, eye3, centre,
                                                              radius, length, walls, wall_count));
    }
    int level = -1;
    if (pixels_per_length >= 0.0f) {
      /* The coarsest level within the budget (level 0's error is 0), and the coarsest
       * within the tighter budget that lets a fish go coarser. */
      int within = 0, within_keep = 0;
      for (int k = 1; k < FF_LOD_LEVELS; ++k) {
        const float pixels = level_errors[k] * pixels_per_length;
        if (pixels <= budget) within = k;
        if (pixels <= keep_budget) within_keep = k;
      }
      const int before = level_of[i];
      level = (before < 0 || within < before) ? within : max(before, within_keep);
    }
    level_of[i] = level;
    if (level >= 0) atomic_inc(&counts[level]);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (item < FF_LOD_LEVELS) group_counts[get_group_id(0) * FF_LOD_LEVELS + item] = counts[item];
}

/* One group of FF_LOD_GROUP work-items over `groups` groups' counts: work-item j sums
 * a contiguous run of groups, an inclusive scan (Hillis-Steele, every level at once)
 * gives each run's start and each level's total, work-item 0 carries the instances
 * without room from level to level, each writes its groups' starts. draw_arguments: per
 * level GL's DrawElementsIndirectCommand (index count, instance count, first index,
 * base vertex, base instance). */
__kernel __attribute__((reqd_work_group_size(FF_LOD_GROUP, 1, 1))) void lod_offsets(
    __global const uint* restrict group_counts, const uint groups,
    __global uint* restrict group_starts, __global const uint* restrict index_counts,
    __global const uint* restrict level_rows, __global uint* restrict own_counts,
    __global uint* restrict level_counts, __global uint* restrict draw_arguments) {
  __local uint runs[FF_LOD_GROUP * FF_LOD_LEVELS];
  const uint item = get_local_id(0);
  const uint per_item = (groups + FF_LOD_GROUP - 1) / FF_LOD_GROUP;
  const uint first = min(groups, item * per_item);
  const uint end = min(groups, first + per_item);
  uint own[FF_LOD_LEVELS];
  for (int k = 0; k < FF_LOD_LEVELS; ++k) {
    uint sum = 0;
    for (uint g = first; g < end; ++g) sum += group_counts[g * FF_LOD_LEVELS + k];
    own[k] = sum;
    runs[item * FF_LOD_LEVELS + k] = sum;
  }
  for (uint offset = 1; offset < FF_LOD_GROUP; offset <<= 1) {
    uint add[FF_LOD_LEVELS];
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int k = 0; k < FF_LOD_LEVELS; ++k) {
      add[k] = item >= offset ? runs[(item - offset) * FF_LOD_LEVELS + k] : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int k = 0; k < FF_LOD_LEVELS; ++k) runs[item * FF_LOD_LEVELS + k] += add[k];
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (item == 0) {
    uint incoming = 0; /* instances that found no room in the finer levels */
    for (int k = 0; k < FF_LOD_LEVELS; ++k) {
      const uint start = runs[(FF_LOD_GROUP - 1) * FF_LOD_LEVELS + k];
      own_counts[k] = start;
      const uint total = start + incoming;
      const uint placed = min(total, level_rows[k]);
      incoming = total - placed;
      level_counts[k] = placed;
      draw_arguments[5 * k] = index_counts[k];
      draw_arguments[5 * k + 1] = placed;
      draw_arguments[5 * k + 2] = 0;
      draw_arguments[5 * k + 3] = 0;
      draw_arguments[5 * k + 4] = 0;
    }
    level_counts[FF_LOD_LEVELS] = incoming; /* drawn at no level */
  }
  for (int k = 0; k < FF_LOD_LEVELS; ++k) {
    uint start = runs[item * FF_LOD_LEVELS + k] - own[k];
    for (uint g = first; g < end; ++g) {
      group_starts[g * FF_LOD_LEVELS + k] = start;
      start += group_counts[g * FF_LOD_LEVELS + k];
    }
  }
}

/* Each level's count of the group's instances before this one, for all levels at once:
 * 16 bits a level in a uint4 (up to 8 levels) or a uint8 (up to 16; a group's counts
 * are at most FF_LOD_GROUP <= 256), summed by an inclusive scan (Hillis-Steele) in
 * local memory. */
#if FF_LOD_LEVELS <= 8
typedef uint4 LodFields;
#else
typedef uint8 LodFields;
#endif

FF_LOD_INLINE LodFields one_hot(int level) {
  LodFields v = (LodFields)(0);
  if (level < 0) return v;
  const uint bit = 1u << (16 * (level & 1));
  switch (level >> 1) {
    case 0: v.s0 = bit; break;
    case 1: v.s1 = bit; break;
    case 2: v.s2 = bit; break;
    case 3: v.s3 = bit; break;
#if FF_LOD_LEVELS > 8
    case 4: v.s4 = bit; break;
    case 5: v.s5 = bit; break;
    case 6: v.s6 = bit; break;
    default: v.s7 = bit; break;
#endif
  }
  return v;
}

FF_LOD_INLINE uint field(LodFields v, int level) {
  uint word;
  switch (level >> 1) {
    case 0: word = v.s0; break;
    case 1: word = v.s1; break;
    case 2: word = v.s2; break;
#if FF_LOD_LEVELS > 8
    case 3: word = v.s3; break;
    case 4: word = v.s4; break;
    case 5: word = v.s5; break;
    case 6: word = v.s6; break;
    default: word = v.s7; break;
#else
    default: word = v.s3; break;
#endif
  }
  return (word >> (16 * (level & 1))) & 0xffffu;
}

__kernel __attribute__((reqd_work_group_size(FF_LOD_GROUP, 1, 1))) void lod_scatter(
    __global const int* restrict level_of, const uint instances,
    __global const uint* restrict group_starts, __global const uint* restrict level_rows,
    __global const uint* restrict own_counts, __global uint* restrict instance_lists) {
  __local LodFields scan[FF_LOD_GROUP];
  const uint item = get_local_id(0);
  const size_t i = get_global_id(0);
  const int level = i < instances ? level_of[i] : -1;
  const LodFields mine = one_hot(level);
  scan[item] = mine;
  for (uint offset = 1; offset < FF_LOD_GROUP; offset <<= 1) {
    barrier(CLK_LOCAL_MEM_FENCE);
    const LodFields add = item >= offset ? scan[item - offset] : (LodFields)(0);
    barrier(CLK_LOCAL_MEM_FENCE);
    scan[item] += add;
  }
  if (level < 0) return;
  const uint before = field(scan[item] - mine, level);
  /* Its place in its level's sequence; past the rows, in the next level's. */
  uint at = group_starts[get_group_id(0) * FF_LOD_LEVELS + level] + before;
  for (int k = level; k < FF_LOD_LEVELS; ++k) {
    const uint rows = level_rows[k];
    if (at < rows) {
      instance_lists[level_rows[FF_LOD_LEVELS + k] + at] = (uint)i;
      return;
    }
    if (k + 1 < FF_LOD_LEVELS) at = own_counts[k + 1] + (at - rows);
  }
}

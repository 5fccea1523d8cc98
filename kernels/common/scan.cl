/* Inclusive scan (Hillis-Steele) of a pair of sums over the `items` work-items that
 * share one instance's table (rig_prepare's spine records, the swim driver's fold
 * clearing), in local memory: item i gets the sums of the values of items 0..i.
 * scratch: 2 items floats of the instance's. `items` is the same for every work-item
 * of the group (1, or the whole group: device_profile.hpp table_group_size), so the barriers are reached by all or none;
 * with one item there is nothing to share and no barrier. The first barrier lets an
 * earlier use of scratch finish before it is written. */
FF_INLINE float2 inclusive_scan2(float2 value, __local float* scratch, int item, int items) {
  if (items == 1) return value;
  barrier(CLK_LOCAL_MEM_FENCE);
  scratch[item] = value.x;
  scratch[items + item] = value.y;
  for (int offset = 1; offset < items; offset <<= 1) {
    barrier(CLK_LOCAL_MEM_FENCE);
    const float add_x = item >= offset ? scratch[item - offset] : 0.0f;
    const float add_y = item >= offset ? scratch[items + item - offset] : 0.0f;
    barrier(CLK_LOCAL_MEM_FENCE);
    scratch[item] += add_x;
    scratch[items + item] += add_y;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  return (float2)(scratch[item], scratch[items + item]);
}

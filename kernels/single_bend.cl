/* The whole-body bend (a rig of one component with one bend stage, METHOD.md
 * section 5) in its own kernel: one work-item per (vertex, FF_INSTANCES_PER_ITEM
 * instances), NDRange (plane_stride, ceil(instances / FF_INSTANCES_PER_ITEM)). Several
 * instances per work-item read the rest vertex once and halve the work-items a GPU
 * must schedule, which is what limits it below its write bandwidth with one; CPUs
 * take 1. The engine picks it for such rigs (ClDeformer::uses_single_bend_kernel):
 * it writes what the rig kernels write, with the back transform as kernel arguments
 * instead of the stage table.
 *
 * rest_*: the rest mesh in the body frame, planes of `stride` floats (padding
 *         vertices hold harmless values: the origin, e_z, e_x).
 * m:      one bend parameter per instance, checked on the host.
 * placements: per instance a world placement record (common/placement.cl), read
 *         when FF_PLACEMENT is 1 instead of the back transform.
 * out_*:  the outputs as their layout says (common/outputs.cl).
 * With FF_INSTANCE_LIST, the instances a list names (common/instance_list.cl): m and
 *         placements at `source`, the outputs at row `instance`.
 * back_*: the way back to mesh coordinates, M^-1 of (2):
 *         p_b = origin + s (x e_x + y e_y + z e_z), n_b = x e_x + y e_y + z e_z;
 *         scaled_axis_* = s e_*, axis_* = e_* (all in mesh coordinates).
 *
 * Build options: FF_BEND_EXACT (deformers/bend.cl), FF_NORMALS_JACOBIAN, those of
 * common/planes.cl and common/outputs.cl, and FF_LANES (common/lanes.cl: FF_LANES
 * consecutive slots per work-item, NDRange (plane_stride / FF_LANES, ...); FinFlex's
 * planes stored as vectors, kernels/cpu/lane_outputs.cl, other layouts lane by lane).
 * No branch depends on the vertex: the planes are padded to the work-group size, and
 * the instance bound is the same for a whole work-group. */

/* x a_x + y a_y + z a_z (+ origin): the way back to mesh coordinates, M^-1 of (2). */
FF_INLINE Vec3 to_mesh(Vec3 v, float4 axis_x, float4 axis_y, float4 axis_z, float4 origin) {
  return vec3(origin.x + v.x * axis_x.x + v.y * axis_y.x + v.z * axis_z.x,
              origin.y + v.x * axis_x.y + v.y * axis_y.y + v.z * axis_z.y,
              origin.z + v.x * axis_x.z + v.y * axis_y.z + v.z * axis_z.z);
}

__kernel void single_bend(__global const float* restrict rest_positions,
                          __global const float* restrict rest_normals,
                          __global const float* restrict rest_tangents,
                          __global const float* restrict m,
                          __global const float* restrict placements, FF_OUTPUT_ARGUMENTS,
                          const uint stride, const uint instances,
                          const float4 origin,
                          const float4 scaled_axis_x, const float4 scaled_axis_y,
                          const float4 scaled_axis_z,
                          const float4 axis_x, const float4 axis_y,
                          const float4 axis_z FF_INSTANCE_LIST_ARGUMENTS) {
  FF_OUTPUT_LOCALS
  const size_t v = FF_FIRST_SLOT;
  const float4 no_offset = (float4)(0.0f);
  const Vec3 rest_p = load_plane3(rest_positions, 0, stride, v);
  const Vec3 rest_n = load_plane3(rest_normals, 0, stride, v);
  const Vec3 rest_t = FF_LOAD_TANGENT(rest_tangents, 0, stride, v);
  FF_EACH_INSTANCE_ROW {
    for (uint k = 0; k < FF_INSTANCES_PER_ITEM; ++k) {
      const size_t instance = first_instance + k;
      if (instance >= listed) break;
      FF_SOURCE_OR_SKIP(source)
      const SecantSample s = bend_sample(rest_p.x, rest_p.z, m[source]);
#if FF_PLACEMENT /* from the body frame straight to the world */
      FF_READ_PLACEMENT(record, placements + source * 16)
      const Vec3 p = world_point(secant_position(rest_p, s), record);
      const Vec3 n = world_direction(secant_normal(rest_n, s), record);
      const Vec3 t = world_direction(secant_tangent(rest_t, s), record);
#else
      const Vec3 p = to_mesh(secant_position(rest_p, s), scaled_axis_x, scaled_axis_y,
                             scaled_axis_z, origin);
      const Vec3 n = to_mesh(secant_normal(rest_n, s), axis_x, axis_y, axis_z, no_offset);
      const Vec3 t = to_mesh(secant_tangent(rest_t, s), axis_x, axis_y, axis_z, no_offset);
#endif
      FF_STORE_OUTPUTS(instance, v)
    }
  }
}

/* The outputs of kernels of more than one lane (kernels/common/lanes.cl) in FinFlex's
 * planes in slot order (finflex/batch.hpp), normals (and tangents) in float32 or half:
 * FF_LANE_PLANES (common/outputs.cl), stored as vectors. Kernels of more than one lane
 * store every other layout lane by lane through common/outputs.cl's stores of one slot.
 *
 * store_outputs and FF_STORE_OUTPUTS keep the names and arguments of
 * common/outputs.cl, so the kernels end alike whatever their lanes. The attributes'
 * places still come from out_layout (offset, plane stride and instance stride, in
 * scalars of the attribute's format); each component's FF_LANES slots are stored as
 * one vector (kernels/cpu/lane_planes.cl: streaming or plain stores, vstoren where a
 * caller's buffer is not aligned to the vectors). */
#if FF_LANE_PLANES

/* Component c of the lanes of instance i from slot v, in `format` (float32 or half):
 * FF_LANES consecutive scalars at offset + i * instance_stride + c * plane_stride + v
 * (with FF_PLANE_STRIDE, the numbers compiled in: common/outputs.cl). */
FF_INLINE void store_lane_attribute(__global float* buffer, const int format, ulong offset,
                                    ulong plane_stride, ulong instance_stride, size_t i,
                                    size_t v, Vec3 value) {
#ifdef FF_PLANE_STRIDE
  plane_stride = FF_PLANE_STRIDE;
  const size_t first = element_index(0, 0, plane_stride, 0, i, v);
#else
  const size_t first = (size_t)(offset + i * instance_stride) + v;
#endif
  if (format == FF_F16X3) {
    __global ushort* halves = (__global ushort*)buffer + first;
    store_half_lanes(halves, value.x);
    store_half_lanes(halves + plane_stride, value.y);
    store_half_lanes(halves + 2 * plane_stride, value.z);
  } else {
    store_lanes(buffer + first, value.x);
    store_lanes(buffer + first + plane_stride, value.y);
    store_lanes(buffer + first + 2 * plane_stride, value.z);
  }
}

FF_INLINE void store_outputs(__global float* out_positions, __global float* out_normals,
                             __global float* out_tangents, __global float* out_previous,
                             ulong16 out_layout, size_t instance, size_t v, Vec3 p, Vec3 n,
                             Vec3 t, float rest_tangent_w) {
  store_lane_attribute(out_positions, FF_F32X3, out_layout.s0, out_layout.s1, out_layout.s2,
                       instance, v, p);
  store_lane_attribute(out_normals, FF_NORMAL_FORMAT, out_layout.s3, out_layout.s4,
                       out_layout.s5, instance, v, n);
#if FF_TANGENTS
  store_lane_attribute(out_tangents, FF_TANGENT_FORMAT, out_layout.s6, out_layout.s7,
                       out_layout.s8, instance, v, t);
#endif
}

#define FF_OUTPUT_LOCALS
#define FF_STORE_OUTPUTS(instance, v)                                                      \
  {                                                                                        \
    store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout,      \
                  instance, v, p, n, t, 1.0f);                                             \
  }
#endif

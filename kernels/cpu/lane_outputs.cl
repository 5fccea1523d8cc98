/* The outputs of kernels of more than one lane (kernels/common/lanes.cl) in FinFlex's
 * planes in slot order (finflex/batch.hpp), normals (and tangents) in float32 or half:
 * FF_LANE_PLANES (common/outputs.cl), stored as vectors; and float32 vertex structs in
 * one buffer (FF_LANE_STRUCT, below), transposed into vectors. Kernels of more than one
 * lane store every other layout lane by lane through common/outputs.cl's stores of one
 * slot.
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

/* A vertex struct of float32x3 attributes that fill its FF_STAGED_FLOATS floats (6, or 9
 * with tangents), all in one buffer, in slot order (finflex/cl_outputs.hpp
 * lane_struct_options; FF_LANE_STRUCT, with the numbers of FF_STAGED_STRUCT,
 * common/outputs.cl): a work-item's FF_LANES structs are one contiguous run. Each native
 * vector of lanes (StoreVector, W of them: kernels/cpu/lane_planes.cl) becomes W structs
 * of F floats, that is F vectors, transposed in registers: output vector k holds the
 * floats W k ... W k + W - 1 of the run, float g being member g % F of the struct of
 * lane g / F. It starts from members 0 and 1 and takes each further member in by one
 * two-vector shuffle (constant indices: a permute instruction each), F - 1 shuffles an
 * output vector. Stored like the planes (streaming where aligned, vstoren elsewhere).
 * Lane by lane, the same structs took F scalar stores a vertex, each after moving its
 * float out of the vector. */
#if FF_LANE_STRUCT && FF_LANES > 1 && !FF_LANE_PLANES
#if FF_LANES == 8
#define FF_STRUCT_WIDTH 8
#else
#define FF_STRUCT_WIDTH 16
#endif
#define FF_STRUCT_F FF_STAGED_FLOATS
/* Element j of output vector k with member m taken in from the second vector: its
 * lane there (W + lane) where float W k + j is member m, else element j as it was. */
/* (k past F, whose code is left out, as 0: its indices must still be valid.) */
#define FF_STRUCT_G(k, j) (FF_STRUCT_WIDTH * ((k) < FF_STRUCT_F ? (k) : 0) + (j))
#define FF_STRUCT_INDEX(k, m, j)                                  \
  (FF_STRUCT_G(k, j) % FF_STRUCT_F == (m)                          \
       ? FF_STRUCT_WIDTH + FF_STRUCT_G(k, j) / FF_STRUCT_F : (j))
/* The first shuffle: members 0 and 1 into their places (lane g / F of either). */
#define FF_STRUCT_FIRST(k, m, j)                                                   \
  (FF_STRUCT_G(k, j) % FF_STRUCT_F == 1 ? FF_STRUCT_WIDTH + FF_STRUCT_G(k, j) / FF_STRUCT_F \
                                        : FF_STRUCT_G(k, j) / FF_STRUCT_F)
#if FF_STRUCT_WIDTH == 8
#define FF_STRUCT_INDICES(M, k, m) \
  M(k, m, 0), M(k, m, 1), M(k, m, 2), M(k, m, 3), M(k, m, 4), M(k, m, 5), M(k, m, 6), M(k, m, 7)
#else
#define FF_STRUCT_INDICES(M, k, m)                                                        \
  M(k, m, 0), M(k, m, 1), M(k, m, 2), M(k, m, 3), M(k, m, 4), M(k, m, 5), M(k, m, 6),     \
      M(k, m, 7), M(k, m, 8), M(k, m, 9), M(k, m, 10), M(k, m, 11), M(k, m, 12),          \
      M(k, m, 13), M(k, m, 14), M(k, m, 15)
#endif
/* Member m taken into r (members past the struct's F: nothing). */
#define FF_STRUCT_TAKE(k, m)                                                            \
  if ((m) < FF_STRUCT_F) {                                                              \
    r = __builtin_shufflevector(r, member[(m) < FF_STRUCT_F ? (m) : 0],                 \
                                FF_STRUCT_INDICES(FF_STRUCT_INDEX, k, m));              \
  }
/* Output vector k (none past F) of the run at `first`. */
#define FF_STRUCT_OUTPUT(k)                                                             \
  if ((k) < FF_STRUCT_F) {                                                              \
    StoreVector r = __builtin_shufflevector(member[0], member[1],                       \
                                            FF_STRUCT_INDICES(FF_STRUCT_FIRST, k, 1));  \
    FF_STRUCT_TAKE(k, 2)                                                                \
    FF_STRUCT_TAKE(k, 3)                                                                \
    FF_STRUCT_TAKE(k, 4)                                                                \
    FF_STRUCT_TAKE(k, 5)                                                                \
    FF_STRUCT_TAKE(k, 6)                                                                \
    FF_STRUCT_TAKE(k, 7)                                                                \
    FF_STRUCT_TAKE(k, 8)                                                                \
    store_vector(first + (k) * FF_STRUCT_WIDTH, r);                                     \
  }

/* The W structs of one native vector of lanes, at `first` (their first float). */
FF_INLINE void store_struct_vectors(__global float* first, StoreVector px, StoreVector py,
                                    StoreVector pz, StoreVector nx, StoreVector ny,
                                    StoreVector nz, StoreVector tx, StoreVector ty,
                                    StoreVector tz) {
  StoreVector member[9]; /* constant indices only: kept in registers */
  member[FF_STAGED_POSITION] = px;
  member[FF_STAGED_POSITION + 1] = py;
  member[FF_STAGED_POSITION + 2] = pz;
  member[FF_STAGED_NORMAL] = nx;
  member[FF_STAGED_NORMAL + 1] = ny;
  member[FF_STAGED_NORMAL + 2] = nz;
#if FF_TANGENTS
  member[FF_STAGED_TANGENT] = tx;
  member[FF_STAGED_TANGENT + 1] = ty;
  member[FF_STAGED_TANGENT + 2] = tz;
#endif
  FF_STRUCT_OUTPUT(0)
  FF_STRUCT_OUTPUT(1)
  FF_STRUCT_OUTPUT(2)
  FF_STRUCT_OUTPUT(3)
  FF_STRUCT_OUTPUT(4)
  FF_STRUCT_OUTPUT(5)
  FF_STRUCT_OUTPUT(6)
  FF_STRUCT_OUTPUT(7)
  FF_STRUCT_OUTPUT(8)
}

/* The work-item's structs of instance i from slot v: the positions' offset less the
 * position's place in the struct is the run's start (as in store_staged). */
FF_INLINE void store_lane_structs(__global float* out, ulong16 out_layout, size_t i, size_t v,
                                  Vec3 p, Vec3 n, Vec3 t) {
  __global float* first = out + (size_t)(out_layout.s0 - FF_STAGED_POSITION + i * out_layout.s2) +
                          v * FF_STRUCT_F;
#if FF_LANES == 32
  store_struct_vectors(first, p.x.lo, p.y.lo, p.z.lo, n.x.lo, n.y.lo, n.z.lo, t.x.lo, t.y.lo,
                       t.z.lo);
  store_struct_vectors(first + 16 * FF_STRUCT_F, p.x.hi, p.y.hi, p.z.hi, n.x.hi, n.y.hi,
                       n.z.hi, t.x.hi, t.y.hi, t.z.hi);
#else
  store_struct_vectors(first, p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y, t.z);
#endif
}

#define FF_OUTPUT_LOCALS
#define FF_STORE_OUTPUTS(instance, v) \
  { store_lane_structs(out_positions, out_layout, instance, v, p, n, t); }
#endif

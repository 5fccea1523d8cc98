/* Output stores (finflex/output_layout.hpp): each attribute in its own format and
 * arrangement, given as build options (so every branch below folds away):
 *   FF_POSITION_FORMAT, FF_NORMAL_FORMAT, FF_TANGENT_FORMAT, FF_PREVIOUS_FORMAT:
 *     the AttributeFormat (FF_F32X3 ...); FF_*_PACKED: 1 packed, 0 planes;
 *   FF_PREVIOUS (0/1): previous-frame positions are written;
 *   FF_MESH_ORDER (0/1): outputs indexed by mesh vertex (vertex_of_slot) instead of slot.
 * and their numbers as the kernel argument `out_layout` (ulong16, in scalars of each
 * attribute's format: 4 bytes for float32 and the octahedral pair, 2 for 16 bits):
 *   s0-s2 positions: offset, step (packed: vertex stride; planes: plane stride),
 *         instance stride; s3-s5 normals; s6-s8 tangents; s9-sb previous positions;
 *   sc    1 when the previous positions' place holds last frame's positions, else 0
 *         (the first frame writes the current positions there: no motion). */
#define FF_F32X3 0
#define FF_F32X4 1
#define FF_F16X3 2
#define FF_F16X4 3
#define FF_S16X4 4
#define FF_OCT16 5

#ifndef FF_POSITION_FORMAT
#define FF_POSITION_FORMAT FF_F32X3
#endif
#ifndef FF_POSITION_PACKED
#define FF_POSITION_PACKED 0
#endif
#ifndef FF_NORMAL_FORMAT
#define FF_NORMAL_FORMAT FF_F32X3
#endif
#ifndef FF_NORMAL_PACKED
#define FF_NORMAL_PACKED 0
#endif
#ifndef FF_TANGENT_FORMAT
#define FF_TANGENT_FORMAT FF_F32X3
#endif
#ifndef FF_TANGENT_PACKED
#define FF_TANGENT_PACKED 0
#endif
#ifndef FF_PREVIOUS
#define FF_PREVIOUS 0
#endif
#ifndef FF_PREVIOUS_FORMAT
#define FF_PREVIOUS_FORMAT FF_F32X3
#endif
#ifndef FF_PREVIOUS_PACKED
#define FF_PREVIOUS_PACKED 0
#endif
#ifndef FF_MESH_ORDER
#define FF_MESH_ORDER 0
#endif

/* FF_LANE_PLANES: kernels of more than one lane (common/lanes.cl) writing FinFlex's
 * planes in slot order (float32 positions, normals and tangents float32 or half, and
 * previous positions, if any, float32 planes), which they store as vectors
 * (kernels/cpu/lane_outputs.cl); so too in mesh order where slot s is mesh vertex s
 * (FF_OUTPUT_LIMIT: slot order without the padding). Kernels of more than one lane
 * store any other layout lane by lane through this file's stores of one slot. */
#define FF_LANE_PLANE_FORMAT(format) ((format) == FF_F32X3 || (format) == FF_F16X3)
#define FF_LANE_PLANES                                                                   \
  (FF_LANES > 1 && FF_POSITION_FORMAT == FF_F32X3 && !FF_POSITION_PACKED &&              \
   FF_LANE_PLANE_FORMAT(FF_NORMAL_FORMAT) && !FF_NORMAL_PACKED &&                        \
   (!FF_TANGENTS || (FF_LANE_PLANE_FORMAT(FF_TANGENT_FORMAT) && !FF_TANGENT_PACKED)) &&  \
   (!FF_PREVIOUS || (FF_PREVIOUS_FORMAT == FF_F32X3 && !FF_PREVIOUS_PACKED)) &&          \
   !FF_MESH_ORDER)

/* The tangents' w (handedness) is written by the 4-component formats. */
#define FF_TANGENT_W                                                          \
  (FF_TANGENTS && (FF_TANGENT_FORMAT == FF_F32X4 || FF_TANGENT_FORMAT == FF_F16X4 || \
                   FF_TANGENT_FORMAT == FF_S16X4))

/* round(clamp(c, -1, 1) * 32767) as int16 bits: GL's snorm16 (c = max(s / 32767, -1)). */
FF_INLINE ushort snorm16_bits(float c) {
  return (ushort)(short)rint(clamp(c, -1.0f, 1.0f) * 32767.0f);
}

/* The octahedral encoding of a unit vector (Cigolle et al. 2014, "A Survey of
 * Efficient Representations for Independent Unit Vectors", section 3.2): project on
 * the octahedron |x| + |y| + |z| = 1, fold the lower half over the diagonals; two
 * snorm16, u in the low half of the word. Branch-free. */
FF_INLINE uint octahedral16_bits(float x, float y, float z) {
  const float inverse_l1 = 1.0f / (fabs(x) + fabs(y) + fabs(z));
  const float u = x * inverse_l1;
  const float v = y * inverse_l1;
  const float folded_u = (1.0f - fabs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
  const float folded_v = (1.0f - fabs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
  const float out_u = z < 0.0f ? folded_u : u;
  const float out_v = z < 0.0f ? folded_v : v;
  return (uint)snorm16_bits(out_u) | ((uint)snorm16_bits(out_v) << 16);
}

/* A half (round to nearest even) at `index` of `buffer`: vstore_half on GPUs (one
 * instruction), half_bits on CPUs (it vectorises; PoCL's vstore_half does not). */
FF_INLINE void store_half_at(__global float* buffer, size_t index, float value) {
#if FF_GPU
  vstore_half(value, index, (__global half*)buffer);
#else
  ((__global ushort*)buffer)[index] = half_bits(value);
#endif
}

/* Element (instance i, vertex v) of an attribute, in scalars of its format: the first
 * component's index and the distance between components (planes: a plane).
 * Build option FF_PLANE_STRIDE (engine/src/cl/output_options.cpp plane_stride_option): every
 * attribute is in FinFlex's planes (finflex/batch.hpp), offset 0, plane stride
 * FF_PLANE_STRIDE and instance stride three planes, so the places are compiled in: one
 * 32 x 32-bit product for the first component, the others at literal distances that
 * the stores take as immediate offsets. Measured on the H200, 10,000 swimming fish:
 * 0.768 ms a frame against 0.822 with the numbers from out_layout. */
#ifdef FF_PLANE_STRIDE
FF_INLINE size_t element_index(const int packed, ulong offset, ulong step, ulong instance_stride,
                               size_t i, size_t v) {
  return (size_t)(uint)i * (size_t)(3u * FF_PLANE_STRIDE) + v;
}
#define FF_COMPONENT_DISTANCE(packed, step) ((size_t)FF_PLANE_STRIDE)
#else
FF_INLINE size_t element_index(const int packed, ulong offset, ulong step, ulong instance_stride,
                               size_t i, size_t v) {
  return (size_t)(offset + i * instance_stride + (packed ? v * step : v));
}
#define FF_COMPONENT_DISTANCE(packed, step) ((packed) ? (size_t)1 : (size_t)(step))
#endif

/* The stores of one vertex slot, from here to FF_STORE_OUTPUTS: a one-lane kernel's
 * work-item stores its slot through them, a kernel of more than one lane each of its
 * lanes in turn (but FinFlex's planes: kernels/cpu/lane_outputs.cl, with the same
 * names). StoreVec3: one slot's vector (Vec3 itself with one lane). */
#if !FF_LANE_PLANES
#if FF_LANES == 1
typedef Vec3 StoreVec3;
#define store_vec3 vec3
#else
typedef struct {
  float x, y, z;
} StoreVec3;
FF_INLINE StoreVec3 store_vec3(float x, float y, float z) {
  StoreVec3 v = {x, y, z};
  return v;
}
#endif

/* Writes (x, y, z, w) as `format`, `packed` or planes (compile-time constants). */
FF_INLINE void store_attribute(__global float* buffer, const int format, const int packed,
                               ulong offset, ulong step, ulong instance_stride, size_t i, size_t v,
                               StoreVec3 value, float w) {
  const size_t first = element_index(packed, offset, step, instance_stride, i, v);
  const size_t apart = FF_COMPONENT_DISTANCE(packed, step);
  if (format == FF_F32X3 || format == FF_F32X4) {
    buffer[first] = value.x;
    buffer[first + apart] = value.y;
    buffer[first + 2 * apart] = value.z;
    if (format == FF_F32X4) buffer[first + 3] = w;
  } else if (format == FF_F16X3 || format == FF_F16X4) {
    store_half_at(buffer, first, value.x);
    store_half_at(buffer, first + apart, value.y);
    store_half_at(buffer, first + 2 * apart, value.z);
    if (format == FF_F16X4) store_half_at(buffer, first + 3, w);
  } else if (format == FF_S16X4) {
    __global ushort* shorts = (__global ushort*)buffer;
    shorts[first] = snorm16_bits(value.x);
    shorts[first + 1] = snorm16_bits(value.y);
    shorts[first + 2] = snorm16_bits(value.z);
    shorts[first + 3] = snorm16_bits(w);
  } else { /* FF_OCT16 */
    ((__global uint*)buffer)[first] = octahedral16_bits(value.x, value.y, value.z);
  }
}

/* A float32 position (float32x3 or float32x4, packed or planes). */
FF_INLINE StoreVec3 load_position_attribute(__global const float* buffer, const int packed,
                                            ulong offset, ulong step, ulong instance_stride,
                                            size_t i, size_t v) {
  const size_t first = element_index(packed, offset, step, instance_stride, i, v);
  const size_t apart = FF_COMPONENT_DISTANCE(packed, step);
  return store_vec3(buffer[first], buffer[first + apart], buffer[first + 2 * apart]);
}

/* Every output of one vertex and instance: the previous position first (read where
 * the position still holds last frame's), then the position, the normal and the
 * tangent. rest_tangent_w: the rest mesh's handedness (FF_TANGENT_W). */
FF_INLINE void store_outputs(__global float* out_positions, __global float* out_normals,
                             __global float* out_tangents, __global float* out_previous,
                             ulong16 out_layout, size_t instance, size_t v, StoreVec3 p,
                             StoreVec3 n, StoreVec3 t, float rest_tangent_w) {
#if FF_PREVIOUS
  const StoreVec3 before = out_layout.sc ? load_position_attribute(out_positions, FF_POSITION_PACKED,
                                                              out_layout.s0, out_layout.s1,
                                                              out_layout.s2, instance, v)
                                    : p;
  store_attribute(out_previous, FF_PREVIOUS_FORMAT, FF_PREVIOUS_PACKED, out_layout.s9,
                  out_layout.sa, out_layout.sb, instance, v, before, 1.0f);
#endif
  store_attribute(out_positions, FF_POSITION_FORMAT, FF_POSITION_PACKED, out_layout.s0,
                  out_layout.s1, out_layout.s2, instance, v, p, 1.0f);
  store_attribute(out_normals, FF_NORMAL_FORMAT, FF_NORMAL_PACKED, out_layout.s3, out_layout.s4,
                  out_layout.s5, instance, v, n, 0.0f);
#if FF_TANGENTS
  store_attribute(out_tangents, FF_TANGENT_FORMAT, FF_TANGENT_PACKED, out_layout.s6,
                  out_layout.s7, out_layout.s8, instance, v, t, rest_tangent_w);
#endif
}

/* The output vertex of slot v: the slot, or its mesh vertex (FF_MESH_ORDER; padding
 * slots have none, FF_NO_VERTEX, and write nothing). */
#define FF_NO_VERTEX 0xffffffffu
#if FF_MESH_ORDER
#define FF_OUTPUT_VERTEX(v) vertex_of_slot[v]
#else
#define FF_OUTPUT_VERTEX(v) ((uint)(v))
#endif

/* The kernels' outputs, after their arguments out_positions, out_normals,
 * out_tangents, out_previous, out_layout and vertex_of_slot (in scope with p, n, t and
 * rest_tangents, stride: the rest planes). */
#if FF_TANGENT_W
#define FF_REST_TANGENT_W(v) rest_tangents[3 * (size_t)stride + (v)]
#else
#define FF_REST_TANGENT_W(v) 1.0f
#endif
/* FF_OUTPUT_LIMIT: slots at or past it are padding and write nothing (mesh order of a
 * model whose slots are its vertices in mesh order). */
#ifdef FF_OUTPUT_LIMIT
#define FF_WRITES_SLOT(v, out_v) ((v) < FF_OUTPUT_LIMIT)
#else
#define FF_WRITES_SLOT(v, out_v) (!FF_MESH_ORDER || (out_v) != FF_NO_VERTEX)
#endif
#ifndef FF_STAGED_STRUCT
#define FF_STAGED_STRUCT 0
#endif
#ifndef FF_LANE_STRUCT
#define FF_LANE_STRUCT 0
#endif
#ifndef FF_LANE_ARRAYS
#define FF_LANE_ARRAYS 0
#endif

#if FF_STAGED_STRUCT
/* A vertex struct of float32x3 attributes that fill its stride, all in one buffer, in
 * slot order (the host sets FF_STAGED_STRUCT on GPUs only, finflex/cl_outputs.hpp
 * staged_struct_options: FF_STAGED_FLOATS floats a vertex, the position, normal and
 * tangent FF_STAGED_POSITION, FF_STAGED_NORMAL and FF_STAGED_TANGENT floats into it).
 * Stored one attribute at a time, a warp's stores would land a stride apart; instead
 * the work-group's 64 structs are put together in local memory and written as the one
 * contiguous run they are, a float per work-item and step (coalesced). Every
 * work-item of a group stores the same instances (the groups are one instance row
 * high), so all of them reach the barriers. */
#define FF_STAGED_GROUP 64 /* ClDeformer::kGroupSize */
#define FF_OUTPUT_LOCALS __local float staged_structs[FF_STAGED_GROUP * FF_STAGED_FLOATS];

FF_INLINE void put_staged(__local float* at, Vec3 value) {
  at[0] = value.x;
  at[1] = value.y;
  at[2] = value.z;
}

FF_INLINE void store_staged(__global float* out, __local float* staged, ulong16 out_layout,
                            size_t instance, size_t v, Vec3 p, Vec3 n, Vec3 t) {
  const uint lid = (uint)get_local_id(0);
  __local float* mine = staged + lid * FF_STAGED_FLOATS;
  put_staged(mine + FF_STAGED_POSITION, p);
  put_staged(mine + FF_STAGED_NORMAL, n);
#if FF_TANGENTS
  put_staged(mine + FF_STAGED_TANGENT, t);
#endif
  barrier(CLK_LOCAL_MEM_FENCE);
  /* The group's first struct: the positions' offset less the position's place in it. */
  const size_t first = (size_t)(out_layout.s0 - FF_STAGED_POSITION + instance * out_layout.s2) +
                       (v - lid) * FF_STAGED_FLOATS;
  for (uint k = 0; k < FF_STAGED_FLOATS; ++k) {
    const uint i = k * FF_STAGED_GROUP + lid;
#ifdef FF_OUTPUT_LIMIT
    /* Padding slots past the last vertex (mesh order): nothing. */
    if (v - lid + i / FF_STAGED_FLOATS >= FF_OUTPUT_LIMIT) continue;
#endif
    out[first + i] = staged[i];
  }
  barrier(CLK_LOCAL_MEM_FENCE); /* the next instance reuses the staging */
}

#define FF_STORE_OUTPUTS(instance, v) \
  { store_staged(out_positions, staged_structs, out_layout, instance, v, p, n, t); }
#elif FF_LANES == 1
#define FF_OUTPUT_LOCALS
#define FF_STORE_OUTPUTS(instance, v)                                                         \
  {                                                                                           \
    const uint out_v = FF_OUTPUT_VERTEX(v);                                                   \
    if (FF_WRITES_SLOT(v, out_v)) {                                                           \
      store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout,       \
                    instance, out_v, p, n, t, FF_REST_TANGENT_W(v));                           \
    }                                                                                         \
  }
#elif !FF_LANE_STRUCT && !FF_LANE_ARRAYS /* else kernels/cpu/lane_outputs.cl's vectors */
/* Lane `lane` of a lanes' vector, as one slot's. */
FF_INLINE StoreVec3 lane_of(Vec3 v, int lane) {
  return store_vec3(FF_FLOAT_LANE(v.x, lane), FF_FLOAT_LANE(v.y, lane), FF_FLOAT_LANE(v.z, lane));
}
/* Each lane's slot v + lane in turn, as a one-lane kernel stores its slot: the
 * arithmetic stays vector code, the stores are the layout's own. */
#define FF_OUTPUT_LOCALS
#define FF_STORE_OUTPUTS(instance, v)                                                         \
  for (int lane = 0; lane < FF_LANES; ++lane) {                                               \
    const size_t slot = (v) + lane;                                                           \
    const uint out_v = FF_OUTPUT_VERTEX(slot);                                                \
    if (FF_WRITES_SLOT(slot, out_v)) {                                                        \
      store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout,       \
                    instance, out_v, lane_of(p, lane), lane_of(n, lane), lane_of(t, lane),    \
                    FF_REST_TANGENT_W(slot));                                                 \
    }                                                                                         \
  }
#endif

#endif

/* The output arguments every deformation kernel ends with (before stride, instances). */
#define FF_OUTPUT_ARGUMENTS                                                           \
  __global float* restrict out_positions, __global float* restrict out_normals,       \
      __global float* restrict out_tangents, __global float* restrict out_previous,   \
      const ulong16 out_layout, __global const uint* restrict vertex_of_slot

/* The outputs of kernels of more than one lane (kernels/common/lanes.cl) in FinFlex's
 * planes in slot order (finflex/batch.hpp), normals (and tangents) in float32 or half,
 * previous positions in float32 planes: FF_LANE_PLANES (common/outputs.cl), stored as
 * vectors; vertex structs in one buffer (FF_LANE_STRUCT, below) and attributes in
 * arrays of their own (FF_LANE_ARRAYS), transposed into vectors. Kernels of more than
 * one lane store every other layout lane by lane through common/outputs.cl's stores of
 * one slot.
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
FF_INLINE size_t lane_attribute_first(ulong offset, ulong instance_stride, size_t i, size_t v) {
#ifdef FF_PLANE_STRIDE
  return element_index(0, 0, FF_PLANE_STRIDE, 0, i, v);
#else
  return (size_t)(offset + i * instance_stride) + v;
#endif
}

FF_INLINE size_t lane_plane_stride(ulong plane_stride) {
#ifdef FF_PLANE_STRIDE
  return FF_PLANE_STRIDE;
#else
  return (size_t)plane_stride;
#endif
}

FF_INLINE void store_lane_attribute(__global float* buffer, const int format, ulong offset,
                                    ulong step, ulong instance_stride, size_t i, size_t v,
                                    Vec3 value, int valid) {
  const size_t first = lane_attribute_first(offset, instance_stride, i, v);
  const size_t plane_stride = lane_plane_stride(step);
  if (format == FF_F16X3) {
    __global ushort* halves = (__global ushort*)buffer + first;
    store_half_lanes(halves, value.x, valid);
    store_half_lanes(halves + plane_stride, value.y, valid);
    store_half_lanes(halves + 2 * plane_stride, value.z, valid);
  } else {
    store_lanes(buffer + first, value.x, valid);
    store_lanes(buffer + first + plane_stride, value.y, valid);
    store_lanes(buffer + first + 2 * plane_stride, value.z, valid);
  }
}

/* Previous-frame positions (FF_PREVIOUS, float32 planes): the positions' own place
 * still holds last frame's, read as vectors before they are overwritten (a caller's
 * plane need not be aligned: vloadn); a batch's first frame (out_layout.sc = 0) writes
 * this frame's own (no motion). Then stored as the positions are. */
FF_INLINE void store_lane_previous(__global float* out_previous, __global const float* out_positions,
                                   ulong16 out_layout, size_t instance, size_t v, Vec3 p,
                                   int valid) {
  Vec3 before = p;
  if (out_layout.sc) {
    const size_t first = lane_attribute_first(out_layout.s0, out_layout.s2, instance, v);
    const size_t plane_stride = lane_plane_stride(out_layout.s1);
    before = vec3(load_lanes_unaligned(out_positions + first, valid, p.x),
                  load_lanes_unaligned(out_positions + first + plane_stride, valid, p.y),
                  load_lanes_unaligned(out_positions + first + 2 * plane_stride, valid, p.z));
  }
  store_lane_attribute(out_previous, FF_F32X3, out_layout.s9, out_layout.sa, out_layout.sb,
                       instance, v, before, valid);
}

FF_INLINE void store_outputs(__global float* out_positions, __global float* out_normals,
                             __global float* out_tangents, __global float* out_previous,
                             ulong16 out_layout, size_t instance, size_t v, Vec3 p, Vec3 n,
                             Vec3 t, float rest_tangent_w) {
  const int valid = FF_VALID_LANES(v);
#if FF_PREVIOUS
  store_lane_previous(out_previous, out_positions, out_layout, instance, v, p, valid);
#endif
  store_lane_attribute(out_positions, FF_F32X3, out_layout.s0, out_layout.s1, out_layout.s2,
                       instance, v, p, valid);
  store_lane_attribute(out_normals, FF_NORMAL_FORMAT, out_layout.s3, out_layout.s4,
                       out_layout.s5, instance, v, n, valid);
#if FF_TANGENTS
  store_lane_attribute(out_tangents, FF_TANGENT_FORMAT, out_layout.s6, out_layout.s7,
                       out_layout.s8, instance, v, t, valid);
#endif
}

#define FF_OUTPUT_LOCALS
#define FF_STORE_OUTPUTS(instance, v)                                                      \
  if (FF_WRITES_LANES(v)) {                                                                \
    store_outputs(out_positions, out_normals, out_tangents, out_previous, out_layout,      \
                  instance, v, p, n, t, 1.0f);                                             \
  }
#endif

/* A vertex struct whose attributes fill it, all in one buffer, in slot order
 * (finflex/cl_outputs.hpp lane_struct_options; FF_LANE_STRUCT): float32x3 or x4
 * positions, normals and tangents in float32x3, float32x4, float16x4, snorm16x4 or
 * octahedral16x2, each attribute starting on a 4-byte word. FF_STAGED_FLOATS is the
 * struct's words, FF_STAGED_POSITION, FF_STAGED_NORMAL and FF_STAGED_TANGENT the word
 * each attribute starts at. A work-item's FF_LANES structs are one contiguous run.
 * Each native vector of lanes (StoreVector, W of them: kernels/cpu/lane_planes.cl)
 * becomes W structs of F words, that is F vectors, transposed in registers: first each
 * member word as a vector over the lanes (two 16-bit values packed into one word as the
 * one-slot stores of common/outputs.cl round them), then output vector k holds the
 * words W k ... W k + W - 1 of the run, word g being member g % F of the struct of lane
 * g / F. It starts from members 0 and 1 and takes each further member in by one
 * two-vector shuffle (constant indices: a permute instruction each), F - 1 shuffles an
 * output vector. Stored like the planes (streaming where aligned, vstoren elsewhere).
 * Lane by lane, the same structs took a scalar store per component, each after moving
 * its value out of the vector. */
/* Each attribute in its own tightly packed array (FF_LANE_ARRAYS, also from
 * lane_struct_options: its vertex stride its format's bytes, starting on a 4-byte word,
 * in slot order, as glTF's accessors and a renderer's separate vertex streams hold
 * them): an array of one-attribute structs, F the format's words, transposed alike, one
 * attribute at a time. */
#if (FF_LANE_STRUCT || FF_LANE_ARRAYS) && FF_LANES > 1 && !FF_LANE_PLANES
#if FF_LANES == 8
#define FF_STRUCT_WIDTH 8
#else
#define FF_STRUCT_WIDTH 16
#endif
/* The most words a struct has: three 4-component float32 attributes. */
#define FF_STRUCT_MOST 12

/* Member words of the 16-bit formats over a native vector of lanes (n of them): two
 * values to a word, the first in its low half. */
#define FF_DEFINE_STRUCT_WORDS(n)                                                       \
  FF_INLINE float##n half_pair_word(float##n a, float##n b) {                           \
    return as_float##n(convert_uint##n(half_bits##n(a)) |                               \
                       (convert_uint##n(half_bits##n(b)) << 16));                       \
  }                                                                                     \
  /* common/outputs.cl snorm16_bits, lane by lane. */                                   \
  FF_INLINE uint##n snorm16_lanes(float##n c) {                                         \
    return as_uint##n(convert_int##n(rint(clamp(c, -1.0f, 1.0f) * 32767.0f))) & 0xffffu; \
  }                                                                                     \
  FF_INLINE float##n snorm_pair_word(float##n a, float##n b) {                          \
    return as_float##n(snorm16_lanes(a) | (snorm16_lanes(b) << 16));                    \
  }                                                                                     \
  /* common/outputs.cl octahedral16_bits, lane by lane. */                              \
  FF_INLINE float##n octahedral_word(float##n x, float##n y, float##n z) {              \
    const float##n inverse_l1 = 1.0f / (fabs(x) + fabs(y) + fabs(z));                   \
    const float##n u = x * inverse_l1;                                                  \
    const float##n v = y * inverse_l1;                                                  \
    const float##n folded_u =                                                           \
        (1.0f - fabs(v)) * (u >= 0.0f ? (float##n)1.0f : (float##n)-1.0f);              \
    const float##n folded_v =                                                           \
        (1.0f - fabs(u)) * (v >= 0.0f ? (float##n)1.0f : (float##n)-1.0f);              \
    const float##n out_u = z < 0.0f ? folded_u : u;                                     \
    const float##n out_v = z < 0.0f ? folded_v : v;                                     \
    return as_float##n(snorm16_lanes(out_u) | (snorm16_lanes(out_v) << 16));            \
  }
#if FF_STRUCT_WIDTH == 8
FF_DEFINE_STRUCT_WORDS(8)
#else
FF_DEFINE_STRUCT_WORDS(16)
#endif

/* The member words of one attribute in `format` from word `at` (w: the fourth
 * component of the 4-component formats, as the one-slot stores write it). */
#define FF_PUT_STRUCT_WORDS(at, format, x, y, z, w)   \
  if ((format) == FF_F32X3 || (format) == FF_F32X4) { \
    member[(at)] = (x);                               \
    member[(at) + 1] = (y);                           \
    member[(at) + 2] = (z);                           \
    if ((format) == FF_F32X4) member[(at) + 3] = (w); \
  } else if ((format) == FF_F16X4) {                  \
    member[(at)] = half_pair_word((x), (y));          \
    member[(at) + 1] = half_pair_word((z), (w));      \
  } else if ((format) == FF_S16X4) {                  \
    member[(at)] = snorm_pair_word((x), (y));         \
    member[(at) + 1] = snorm_pair_word((z), (w));     \
  } else { /* FF_OCT16 */                             \
    member[(at)] = octahedral_word((x), (y), (z));    \
  }

/* Element j of output vector k of a struct of F words with member m taken in from the
 * second vector: its lane there (W + lane) where word W k + j is member m, else
 * element j as it was. (k past F, whose code is left out, as 0: its indices must still
 * be valid.) */
#define FF_STRUCT_G(F, k, j) (FF_STRUCT_WIDTH * ((k) < (F) ? (k) : 0) + (j))
#define FF_STRUCT_INDEX(F, k, m, j) \
  (FF_STRUCT_G(F, k, j) % (F) == (m) ? FF_STRUCT_WIDTH + FF_STRUCT_G(F, k, j) / (F) : (j))
/* The first shuffle: members 0 and 1 into their places (lane g / F of either). */
#define FF_STRUCT_FIRST(F, k, m, j)                                                \
  (FF_STRUCT_G(F, k, j) % (F) == 1 ? FF_STRUCT_WIDTH + FF_STRUCT_G(F, k, j) / (F) \
                                   : FF_STRUCT_G(F, k, j) / (F))
#if FF_STRUCT_WIDTH == 8
#define FF_STRUCT_INDICES(M, F, k, m)                                                   \
  M(F, k, m, 0), M(F, k, m, 1), M(F, k, m, 2), M(F, k, m, 3), M(F, k, m, 4), M(F, k, m, 5), \
      M(F, k, m, 6), M(F, k, m, 7)
#else
#define FF_STRUCT_INDICES(M, F, k, m)                                                   \
  M(F, k, m, 0), M(F, k, m, 1), M(F, k, m, 2), M(F, k, m, 3), M(F, k, m, 4), M(F, k, m, 5), \
      M(F, k, m, 6), M(F, k, m, 7), M(F, k, m, 8), M(F, k, m, 9), M(F, k, m, 10),          \
      M(F, k, m, 11), M(F, k, m, 12), M(F, k, m, 13), M(F, k, m, 14), M(F, k, m, 15)
#endif
/* Member m taken into r (members past the struct's F: nothing). */
#define FF_STRUCT_TAKE(F, k, m)                                          \
  if ((m) < (F)) {                                                       \
    r = __builtin_shufflevector(r, member[(m) < (F) ? (m) : 0],          \
                                FF_STRUCT_INDICES(FF_STRUCT_INDEX, F, k, m)); \
  }
/* Output vector k (none past F) of the run at `first`. */
#define FF_STRUCT_OUTPUT(F, k)                                                         \
  if ((k) < (F)) {                                                                     \
    StoreVector r = __builtin_shufflevector(member[0], member[1],                      \
                                            FF_STRUCT_INDICES(FF_STRUCT_FIRST, F, k, 1)); \
    FF_STRUCT_TAKE(F, k, 2)                                                            \
    FF_STRUCT_TAKE(F, k, 3)                                                            \
    FF_STRUCT_TAKE(F, k, 4)                                                            \
    FF_STRUCT_TAKE(F, k, 5)                                                            \
    FF_STRUCT_TAKE(F, k, 6)                                                            \
    FF_STRUCT_TAKE(F, k, 7)                                                            \
    FF_STRUCT_TAKE(F, k, 8)                                                            \
    FF_STRUCT_TAKE(F, k, 9)                                                            \
    FF_STRUCT_TAKE(F, k, 10)                                                           \
    FF_STRUCT_TAKE(F, k, 11)                                                           \
    store_vector(first + (k) * FF_STRUCT_WIDTH, r, valid - (k) * FF_STRUCT_WIDTH);     \
  }
/* The run of W structs of F words from `member` (in scope, with `first` and `valid`, the
 * run's words that are outputs). */
#define FF_STORE_STRUCT_RUN(F) \
  FF_STRUCT_OUTPUT(F, 0)       \
  FF_STRUCT_OUTPUT(F, 1)       \
  FF_STRUCT_OUTPUT(F, 2)       \
  FF_STRUCT_OUTPUT(F, 3)       \
  FF_STRUCT_OUTPUT(F, 4)       \
  FF_STRUCT_OUTPUT(F, 5)       \
  FF_STRUCT_OUTPUT(F, 6)       \
  FF_STRUCT_OUTPUT(F, 7)       \
  FF_STRUCT_OUTPUT(F, 8)       \
  FF_STRUCT_OUTPUT(F, 9)       \
  FF_STRUCT_OUTPUT(F, 10)      \
  FF_STRUCT_OUTPUT(F, 11)

/* The lanes' tangent w from the rest planes' fourth (common/outputs.cl
 * FF_REST_TANGENT_W; rest_tangents and stride in scope); kernels without them (the
 * benchmarks' write-only kernel) define it as they need. */
#if FF_TANGENT_W
#define FF_LANE_TANGENT_W(v) load_lanes(rest_tangents + 3 * (size_t)stride + (v))
#else
#define FF_LANE_TANGENT_W(v) ((LaneFloat)1.0f)
#endif
#define FF_OUTPUT_LOCALS

#if FF_LANE_STRUCT
#define FF_STRUCT_F FF_STAGED_FLOATS

/* The W structs of one native vector of lanes, at `first` (their first word); tw:
 * the tangents' w (the rest mesh's handedness); valid: the words that are outputs. */
FF_INLINE void store_struct_vectors(__global float* first, StoreVector px, StoreVector py,
                                    StoreVector pz, StoreVector nx, StoreVector ny,
                                    StoreVector nz, StoreVector tx, StoreVector ty,
                                    StoreVector tz, StoreVector tw, int valid) {
  /* Constant indices only: kept in registers. Sized past the most words a struct has,
   * so that the formats' branches left out still index within it. */
  StoreVector member[FF_STRUCT_MOST + 4];
  FF_PUT_STRUCT_WORDS(FF_STAGED_POSITION, FF_POSITION_FORMAT, px, py, pz, (StoreVector)1.0f)
  FF_PUT_STRUCT_WORDS(FF_STAGED_NORMAL, FF_NORMAL_FORMAT, nx, ny, nz, (StoreVector)0.0f)
#if FF_TANGENTS
  FF_PUT_STRUCT_WORDS(FF_STAGED_TANGENT, FF_TANGENT_FORMAT, tx, ty, tz, tw)
#endif
  FF_STORE_STRUCT_RUN(FF_STRUCT_F)
}

/* The work-item's structs of instance i from slot v: the positions' offset less the
 * position's place in the struct is the run's start (as in store_staged); tw: the
 * lanes' tangent w. */
FF_INLINE void store_lane_structs(__global float* out, ulong16 out_layout, size_t i, size_t v,
                                  Vec3 p, Vec3 n, Vec3 t, LaneFloat tw) {
  __global float* first = out + (size_t)(out_layout.s0 - FF_STAGED_POSITION + i * out_layout.s2) +
                          v * FF_STRUCT_F;
  const int valid = FF_VALID_LANES(v) * FF_STRUCT_F;
#if FF_LANES == 32
  store_struct_vectors(first, p.x.lo, p.y.lo, p.z.lo, n.x.lo, n.y.lo, n.z.lo, t.x.lo, t.y.lo,
                       t.z.lo, tw.lo, valid);
  store_struct_vectors(first + 16 * FF_STRUCT_F, p.x.hi, p.y.hi, p.z.hi, n.x.hi, n.y.hi,
                       n.z.hi, t.x.hi, t.y.hi, t.z.hi, tw.hi, valid - 16 * FF_STRUCT_F);
#else
  store_struct_vectors(first, p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y, t.z, tw, valid);
#endif
}

#define FF_STORE_OUTPUTS(instance, v)                                                       \
  if (FF_WRITES_LANES(v)) {                                                                 \
    store_lane_structs(out_positions, out_layout, instance, v, p, n, t, FF_LANE_TANGENT_W(v)); \
  }

#else /* FF_LANE_ARRAYS */
/* A format's 4-byte words, and its scalars to a word (out_layout counts in scalars). */
#define FF_FORMAT_WORDS(format) \
  ((format) == FF_F32X3 ? 3 : (format) == FF_F32X4 ? 4 : (format) == FF_OCT16 ? 1 : 2)
#define FF_FORMAT_SCALARS_PER_WORD(format) \
  ((format) == FF_F16X4 || (format) == FF_S16X4 ? 2 : 1)

/* store_<attribute>_vectors(first, x, y, z, w, valid): the W one-attribute structs of
 * one native vector of lanes at `first`, `valid` of their words outputs. */
#define FF_DEFINE_ARRAY_STORE(name, format)                                              \
  FF_INLINE void name(__global float* first, StoreVector x, StoreVector y, StoreVector z, \
                      StoreVector w, int valid) {                                        \
    StoreVector member[FF_STRUCT_MOST + 4];                                              \
    FF_PUT_STRUCT_WORDS(0, format, x, y, z, w)                                           \
    FF_STORE_STRUCT_RUN(FF_FORMAT_WORDS(format))                                         \
  }
FF_DEFINE_ARRAY_STORE(store_position_vectors, FF_POSITION_FORMAT)
FF_DEFINE_ARRAY_STORE(store_normal_vectors, FF_NORMAL_FORMAT)
#if FF_TANGENTS
FF_DEFINE_ARRAY_STORE(store_tangent_vectors, FF_TANGENT_FORMAT)
#endif

/* The first word of (instance i, slot v) of an array at (offset, instance stride), in
 * scalars of its format. */
#define FF_ARRAY_FIRST(buffer, format, offset, instance_stride, i, v)          \
  ((buffer) + (size_t)((offset) + (i) * (instance_stride)) /                   \
                  FF_FORMAT_SCALARS_PER_WORD(format) +                         \
   (v) * FF_FORMAT_WORDS(format))

/* One attribute's lanes (x, y, z, w), native vector by native vector (`valid` lanes in
 * scope). */
#if FF_LANES == 32
#define FF_STORE_ARRAY(store, format, first, x, y, z, w)                                   \
  {                                                                                        \
    store(first, (x).lo, (y).lo, (z).lo, (w).lo, valid * FF_FORMAT_WORDS(format));         \
    store((first) + 16 * FF_FORMAT_WORDS(format), (x).hi, (y).hi, (z).hi, (w).hi,          \
          (valid - 16) * FF_FORMAT_WORDS(format));                                         \
  }
#else
#define FF_STORE_ARRAY(store, format, first, x, y, z, w) \
  store(first, x, y, z, w, valid * FF_FORMAT_WORDS(format));
#endif

/* The work-item's lanes of instance i from slot v into each attribute's array (w: the
 * fourth component as the one-slot stores write it: 1 for positions, 0 for normals,
 * the rest mesh's handedness tw for tangents). */
FF_INLINE void store_lane_arrays(__global float* out_positions, __global float* out_normals,
                                 __global float* out_tangents, ulong16 out_layout, size_t i,
                                 size_t v, Vec3 p, Vec3 n, Vec3 t, LaneFloat tw) {
  const int valid = FF_VALID_LANES(v);
  FF_STORE_ARRAY(store_position_vectors, FF_POSITION_FORMAT,
                 FF_ARRAY_FIRST(out_positions, FF_POSITION_FORMAT, out_layout.s0, out_layout.s2,
                                i, v),
                 p.x, p.y, p.z, (LaneFloat)1.0f)
  FF_STORE_ARRAY(store_normal_vectors, FF_NORMAL_FORMAT,
                 FF_ARRAY_FIRST(out_normals, FF_NORMAL_FORMAT, out_layout.s3, out_layout.s5, i,
                                v),
                 n.x, n.y, n.z, (LaneFloat)0.0f)
#if FF_TANGENTS
  FF_STORE_ARRAY(store_tangent_vectors, FF_TANGENT_FORMAT,
                 FF_ARRAY_FIRST(out_tangents, FF_TANGENT_FORMAT, out_layout.s6, out_layout.s8,
                                i, v),
                 t.x, t.y, t.z, tw)
#endif
}

#define FF_STORE_OUTPUTS(instance, v)                                                     \
  if (FF_WRITES_LANES(v)) {                                                               \
    store_lane_arrays(out_positions, out_normals, out_tangents, out_layout, instance, v, p, \
                      n, t, FF_LANE_TANGENT_W(v));                                        \
  }
#endif
#endif

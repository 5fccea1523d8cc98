/* Structure-of-arrays planes (finflex/batch.hpp): component c of vertex v of an
 * array whose planes start at `first_plane` is planes[(first_plane + c) * stride + v]:
 * the rest mesh and the multi-pass scratch sets (the outputs: common/outputs.cl).
 * FF_GPU (set by the host) is 1 on GPUs. */
#ifndef FF_GPU
#define FF_GPU 0
#endif

/* The batch's shape, set by the host for every batch kernel:
 *   FF_TANGENTS (0/1)        the mesh has tangents (a third array of planes)
 *   FF_INSTANCES_PER_ITEM    instances one work-item deforms: NDRange (slots,
 *                            ceil(instances / FF_INSTANCES_PER_ITEM)) */
#ifndef FF_TANGENTS
#define FF_TANGENTS 0
#endif
#ifndef FF_INSTANCES_PER_ITEM
#define FF_INSTANCES_PER_ITEM 1
#endif

/* One slot per work-item here; kernels/cpu/lane_planes.cl has the same functions over
 * FF_LANES slots. */
#if FF_LANES == 1
FF_INLINE Vec3 load_plane3(__global const float* planes, size_t first_plane, size_t stride,
                        size_t v) {
  return vec3(planes[first_plane * stride + v], planes[(first_plane + 1) * stride + v],
              planes[(first_plane + 2) * stride + v]);
}

FF_INLINE void store_plane3(__global float* planes, size_t first_plane, size_t stride, size_t v,
                         Vec3 value) {
  planes[first_plane * stride + v] = value.x;
  planes[(first_plane + 1) * stride + v] = value.y;
  planes[(first_plane + 2) * stride + v] = value.z;
}
#endif


/* The IEEE half nearest to f (ties to even), as bits: F. Giesen's
 * float_to_half_fast3_rtne with its branches as selects, so it vectorises (PoCL's
 * vstore_half converts element by element). Overflow gives Inf, NaN stays NaN.
 * FF_DEFINE_HALF_BITS(n) defines half_bits##n on float##n: half_bits on a float here,
 * half_bits8 and half_bits16 on the lanes' vectors (kernels/cpu/lane_planes.cl), one
 * rounding for every kernel. */
#define FF_DEFINE_HALF_BITS(n)                                                           \
  FF_INLINE ushort##n half_bits##n(float##n f) {                                         \
    const uint##n sign = as_uint##n(f) & 0x80000000u;                                    \
    const uint##n magnitude = as_uint##n(f) ^ sign;                                      \
    /* Subnormal or zero half: add 0.5 (magic) so the FPU rounds the low bits away. */   \
    const uint denormal_magic = ((127u - 15u) + (23u - 10u) + 1u) << 23;                 \
    const uint##n small =                                                                \
        as_uint##n(as_float##n(magnitude) + as_float(denormal_magic)) - denormal_magic;  \
    /* Normal half: rebias the exponent, round to nearest even on bit 13. */             \
    const uint##n odd = (magnitude >> 13) & 1u;                                          \
    const uint##n normal = (magnitude + (((uint)(15 - 127)) << 23) + 0xfffu + odd) >> 13; \
    const uint##n special =                                                              \
        magnitude > (255u << 23) ? (uint##n)0x7e00u : (uint##n)0x7c00u; /* NaN : Inf */  \
    const uint##n bits = magnitude >= ((127u + 16u) << 23) ? special                     \
                         : magnitude < (113u << 23)        ? small                       \
                                                           : normal;                     \
    return convert_ushort##n(bits | (sign >> 16));                                       \
  }

FF_DEFINE_HALF_BITS()

/* Tangents only when the batch has them (the placeholder direction otherwise). */
#if FF_TANGENTS
#define FF_LOAD_TANGENT(planes, first, stride, v) load_plane3(planes, first, stride, v)
#else
#define FF_LOAD_TANGENT(planes, first, stride, v) vec3(1.0f, 0.0f, 0.0f)
#endif

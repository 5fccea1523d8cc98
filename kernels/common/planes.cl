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


/* The IEEE half nearest to f (ties to even), as bits. FF_DEFINE_HALF_BITS(n) defines
 * half_bits##n on float##n: half_bits on a float here, half_bits8 and half_bits16 on the
 * lanes' vectors (kernels/cpu/lane_planes.cl), one rounding for every kernel.
 *
 * Where the CPU converts in hardware (x86's F16C: vcvtps2ph, up to 16 lanes in one
 * instruction, to nearest even), clang's _Float16 conversion, which compiles to it:
 * the same bits as the software rounding below for every float but a NaN's payload (a
 * NaN stays a NaN). The software rounding took about 20 vector operations a component.
 * Build option FF_SOFTWARE_HALF (0/1): 1 takes the software rounding everywhere (the
 * tests compare the two). */
#ifndef FF_SOFTWARE_HALF
#define FF_SOFTWARE_HALF 0
#endif
#if defined(__clang__) && defined(__F16C__) && !FF_GPU && !FF_SOFTWARE_HALF
typedef _Float16 HalfValue;
typedef _Float16 HalfValue8 __attribute__((ext_vector_type(8)));
typedef _Float16 HalfValue16 __attribute__((ext_vector_type(16)));
FF_INLINE HalfValue to_half_value(float f) { return (HalfValue)f; }
FF_INLINE HalfValue8 to_half_value8(float8 f) { return __builtin_convertvector(f, HalfValue8); }
FF_INLINE HalfValue16 to_half_value16(float16 f) { return __builtin_convertvector(f, HalfValue16); }
#define FF_DEFINE_HALF_BITS(n)                              \
  FF_INLINE ushort##n half_bits##n(float##n f) {            \
    return __builtin_astype(to_half_value##n(f), ushort##n); \
  }
#else
/* In software: F. Giesen's float_to_half_fast3_rtne with its branches as selects, so it
 * vectorises (PoCL's vstore_half converts element by element). Overflow gives Inf, NaN
 * stays NaN. */
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
#endif

FF_DEFINE_HALF_BITS()

/* Tangents only when the batch has them (the placeholder direction otherwise). */
#if FF_TANGENTS
#define FF_LOAD_TANGENT(planes, first, stride, v) load_plane3(planes, first, stride, v)
#else
#define FF_LOAD_TANGENT(planes, first, stride, v) vec3(1.0f, 0.0f, 0.0f)
#endif

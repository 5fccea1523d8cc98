/* Structure-of-arrays planes (finflex/batch.hpp): component c of vertex v of an
 * array whose planes start at `first_plane` is planes[(first_plane + c) * stride + v].
 *
 * Build option FF_HALF_NORMALS (0/1): the outputs' normals and tangents are IEEE
 * halves (round to nearest even) instead of float32, converted with vstore_half on
 * GPUs (FF_GPU, set by the host: one instruction) and with half_bits below on CPUs
 * (PoCL's vstore_half does not vectorise). */
#ifndef FF_HALF_NORMALS
#define FF_HALF_NORMALS 0
#endif
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
 * vstore_half converts element by element). Overflow gives Inf, NaN stays NaN. */
FF_INLINE ushort half_bits(float f) {
  const uint sign = as_uint(f) & 0x80000000u;
  const uint magnitude = as_uint(f) ^ sign;
  /* Subnormal or zero half: add 0.5 (magic) so the FPU rounds the low bits away. */
  const uint denormal_magic = ((127u - 15u) + (23u - 10u) + 1u) << 23;
  const uint small = as_uint(as_float(magnitude) + as_float(denormal_magic)) - denormal_magic;
  /* Normal half: rebias the exponent, round to nearest even on bit 13. */
  const uint odd = (magnitude >> 13) & 1u;
  const uint normal = (magnitude + (((uint)(15 - 127)) << 23) + 0xfffu + odd) >> 13;
  const uint special = magnitude > (255u << 23) ? 0x7e00u : 0x7c00u; /* NaN : Inf */
  const uint bits = magnitude >= ((127u + 16u) << 23) ? special
                    : magnitude < (113u << 23)        ? small
                                                      : normal;
  return (ushort)(bits | (sign >> 16));
}

/* A normal or tangent into an output array, in the batch's normal format. */
#if FF_LANES == 1
FF_INLINE void store_direction3(__global float* planes, size_t first_plane, size_t stride,
                                size_t v, Vec3 value) {
#if FF_HALF_NORMALS && FF_GPU
  __global half* halves = (__global half*)planes;
  vstore_half(value.x, first_plane * stride + v, halves); /* round to nearest even */
  vstore_half(value.y, (first_plane + 1) * stride + v, halves);
  vstore_half(value.z, (first_plane + 2) * stride + v, halves);
#elif FF_HALF_NORMALS
  __global ushort* halves = (__global ushort*)planes;
  halves[first_plane * stride + v] = half_bits(value.x);
  halves[(first_plane + 1) * stride + v] = half_bits(value.y);
  halves[(first_plane + 2) * stride + v] = half_bits(value.z);
#else
  store_plane3(planes, first_plane, stride, v, value);
#endif
}
#endif

/* Tangents only when the batch has them (the placeholder direction otherwise). */
#if FF_TANGENTS
#define FF_LOAD_TANGENT(planes, first, stride, v) load_plane3(planes, first, stride, v)
#define FF_STORE_TANGENT(planes, first, stride, v, value) \
  store_direction3(planes, first, stride, v, value)
#else
#define FF_LOAD_TANGENT(planes, first, stride, v) vec3(1.0f, 0.0f, 0.0f)
#define FF_STORE_TANGENT(planes, first, stride, v, value)
#endif

/* World placement (finflex/placement.hpp), the last stage of every deformation kernel
 * when FF_PLACEMENT is 1: per instance a record of 16 floats, the columns of M (0-8),
 * the translation t (9-11) and s_x / length (12); world(p) = M p + t, directions
 * (M d) s_x / length (M is a rotation times length / s_x, so they stay unit). */
#ifndef FF_PLACEMENT
#define FF_PLACEMENT 0
#endif

FF_INLINE Vec3 place_linear(Vec3 v, __global const float* r) {
  return vec3(v.x * r[0] + v.y * r[3] + v.z * r[6], v.x * r[1] + v.y * r[4] + v.z * r[7],
              v.x * r[2] + v.y * r[5] + v.z * r[8]);
}

FF_INLINE void place_vertex(Vec3* p, Vec3* n, Vec3* t, __global const float* r) {
  const Vec3 moved = place_linear(*p, r);
  *p = vec3(moved.x + r[9], moved.y + r[10], moved.z + r[11]);
  const Vec3 normal = place_linear(*n, r);
  const Vec3 tangent = place_linear(*t, r);
  const float inverse_scale = r[12];
  *n = vec3(normal.x * inverse_scale, normal.y * inverse_scale, normal.z * inverse_scale);
  *t = vec3(tangent.x * inverse_scale, tangent.y * inverse_scale, tangent.z * inverse_scale);
}

/* Places the kernel's p, n, t for `instance` (kernels take `placements`). */
#if FF_PLACEMENT
#define FF_PLACE(instance) place_vertex(&p, &n, &t, placements + (instance) * 16);
#else
#define FF_PLACE(instance)
#endif

/* The fish bend of the paper (METHOD.md section 5), one vertex in the body frame.
 *
 * Everything is written with u = 2 m x, the slope of the bent spine z = m x^2.
 * Valid range (13): |m| <= 0.5 / x_max, so u lies in [-1, 1]; u is clamped there so
 * float rounding at the limit cannot produce NaN.
 *
 * Build options:
 *   FF_BEND_EXACT        0: the paper's series (15)-(17); 1: the closed form (asin)
 *   FF_NORMALS_JACOBIAN  0: normals rotated by (8); 1: normals by the Jacobian's cofactor
 */
#ifndef FF_BEND_EXACT
#define FF_BEND_EXACT 0
#endif
#ifndef FF_NORMALS_JACOBIAN
#define FF_NORMALS_JACOBIAN 0
#endif

/* Floor on sqrt(1 - u^2) where the exact bend's curvature 2m / sqrt(1 - u^2) is
 * infinite; the CPU reference uses the same floor. */
#define FF_MIN_SPINE_COSINE 1e-6f

/* The bent secant surface at one x of the spine.
 *   spine_x, spine_z: f(x, 0) = (x', 0, z') of (16) or its exact counterpart
 *   sin_t, cos_t:     unit secant normal n = (-sin_t, 0, cos_t) (17); the rotation (8)
 *                     taking e_z to n is the rotation about e_y by -theta
 *   along, across:    Jacobian weights. J = R diag(D, 1, 1) with D = |df/dx| (1 - z k),
 *                     k the spine curvature (METHOD.md section 6). Normals go by the
 *                     cofactor R diag(1, D, D), tangents by R diag(D, 1, 1); both are
 *                     renormalised, so any common positive factor may be dropped:
 *                     normal ~ R (along n_x, across n_y, across n_z),
 *                     tangent ~ R (across t_x, along t_y, along t_z). */
typedef struct {
  float spine_x, spine_z;
  float sin_t, cos_t;
  float along, across;
} BendSample;

inline BendSample bend_sample(float x, float z, float m) {
  const float u = clamp(2.0f * m * x, -1.0f, 1.0f);
  const float u2 = u * u;
  BendSample s;
  s.spine_z = 0.5f * u * x; /* m x^2 */
#if FF_BEND_EXACT
  /* x' = x sqrt(1 - u^2) / 2 + asin(u) / (4m) = x (c + asin(u) / u) / 2;
   * asin(u) / u -> 1 + u^2/6 + 3u^4/40 near 0. (1 - u)(1 + u) keeps c accurate at |u| -> 1. */
  const float c = sqrt((1.0f - u) * (1.0f + u));
  const float asin_u_over_u =
      fabs(u) < 1e-2f ? 1.0f + u2 * (1.0f / 6.0f + u2 * (3.0f / 40.0f)) : asin(u) / u;
  s.spine_x = 0.5f * x * (c + asin_u_over_u);
  s.sin_t = u;
  s.cos_t = c;
  /* |df/dx| = 1, k = 2m / c: scaled by c, (along, across) = (c, c - 2 m z). */
  const float c_floor = fmax(c, FF_MIN_SPINE_COSINE);
  s.along = c_floor;
  s.across = c_floor - 2.0f * m * z;
#else
  /* (15): x' = x (1 - 2/3 m^2x^2 - 2/5 m^4x^4) = x (1 - u^2/6 - u^4/40);
   * df/dx = (a, 0, u), a = 1 - 2m^2x^2 - 2m^4x^4 = 1 - u^2/2 - u^4/8 (16);
   * n = (-u, 0, a) / g, g = |df/dx| (17). */
  const float a = 1.0f - u2 * (0.5f + 0.125f * u2);
  const float g2 = a * a + u2;
  const float g = sqrt(g2);
  s.spine_x = x * (1.0f - u2 * (1.0f / 6.0f + u2 * (1.0f / 40.0f)));
  s.sin_t = u / g;
  s.cos_t = a / g;
  /* k = (a u' - u a') / g^3 with u' = 2m, a' = -2m (u + u^3/2):
   * D g^2 = g^3 - z 2m (1 + u^2/2 + 3u^4/8); scaled by g^2: (along, across) = (g^2, D g^2). */
  s.along = g2;
  s.across = g2 * g - z * 2.0f * m * (1.0f + u2 * (0.5f + 0.375f * u2));
#endif
  return s;
}

/* (7): p' = f(x, y, 0) + z n. */
inline float3 bend_position(float3 p, BendSample s) {
  return (float3)(s.spine_x - p.z * s.sin_t, p.y, s.spine_z + p.z * s.cos_t);
}

/* R v: the rotation about e_y taking e_z to n = (-sin_t, 0, cos_t). */
inline float3 rotate_to_secant_normal(float3 v, BendSample s) {
  return (float3)(s.cos_t * v.x - s.sin_t * v.z, v.y, s.sin_t * v.x + s.cos_t * v.z);
}

inline float3 bend_normal(float3 n, BendSample s) {
#if FF_NORMALS_JACOBIAN
  n = (float3)(s.along * n.x, s.across * n.y, s.across * n.z);
#endif
  return normalize(rotate_to_secant_normal(n, s));
}

inline float3 bend_tangent(float3 t, BendSample s) {
#if FF_NORMALS_JACOBIAN
  t = (float3)(s.across * t.x, s.along * t.y, s.along * t.z);
#endif
  return normalize(rotate_to_secant_normal(t, s));
}

/* Secant-surface deformers of one vertex in its stage's local frame: the fish bend of
 * the paper (METHOD.md section 5), paper and exact, and the hinge (section 6).
 *
 * Everything is written with u = 2 m x, the slope of the bent spine z = m x^2.
 * Valid range (13): |m| <= 0.5 / x_max, so u lies in [-1, 1]; u is clamped there so
 * float rounding at the limit cannot produce NaN.
 *
 * Build options:
 *   FF_BEND_EXACT        0: the paper's series (15)-(17); 1: the closed form (asin)
 *   FF_NORMALS_JACOBIAN  0: normals rotated by (8); 1: normals by the Jacobian's cofactor
 */
/* Every helper is inlined into its kernel: PoCL vectorises a kernel across work-items
 * only when no call is left in it. */
#define FF_INLINE inline __attribute__((always_inline))

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

/* asin(u) / u for u in [-1, 1], without branches and without the 0/0 at u = 0, so the
 * exact bend vectorises and is smooth through m = 0. Cephes' asinf: for |u| <= 1/2,
 * asin(u) = u + u z P(z) with z = u^2, so asin(u)/u = 1 + z P(z); for |u| > 1/2,
 * asin(|u|) = pi/2 - 2 asin(sqrt(z)) with z = (1 - |u|)/2. Relative error 2.5e-7. */
FF_INLINE float asin_over_u(float u) {
  const float a = fabs(u);
  const int big = a > 0.5f;
  const float z = big ? 0.5f * (1.0f - a) : a * a;
  const float root = sqrt(z);
  const float p = ((((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z +
                    7.4953002686e-2f) * z + 1.6666752422e-1f) * z;
  const float small_ratio = 1.0f + p;                                   /* |u| <= 1/2 */
  const float big_ratio = (M_PI_2_F - 2.0f * (root + root * p)) / fmax(a, 0.5f);
  return big ? big_ratio : small_ratio;
}

/* Exact bend: x' = x sqrt(1 - u^2) / 2 + asin(u) / (4m) = x (c + asin(u) / u) / 2;
 * (1 - u)(1 + u) keeps c accurate as |u| -> 1. |df/dx| = 1, k = 2m / c: scaled by c,
 * (along, across) = (c, c - 2 m z). */
FF_INLINE BendSample bend_sample_exact(float x, float z, float m) {
  const float u = clamp(2.0f * m * x, -1.0f, 1.0f);
  const float c = sqrt((1.0f - u) * (1.0f + u));
  const float c_floor = fmax(c, FF_MIN_SPINE_COSINE);
  BendSample s;
  s.spine_x = 0.5f * x * (c + asin_over_u(u));
  s.spine_z = 0.5f * u * x; /* m x^2 */
  s.sin_t = u;
  s.cos_t = c;
  s.along = c_floor;
  s.across = c_floor - 2.0f * m * z;
  return s;
}

/* The paper's bend. (15): x' = x (1 - 2/3 m^2x^2 - 2/5 m^4x^4) = x (1 - u^2/6 - u^4/40);
 * df/dx = (a, 0, u), a = 1 - 2m^2x^2 - 2m^4x^4 = 1 - u^2/2 - u^4/8 (16);
 * n = (-u, 0, a) / g, g = |df/dx| (17). k = (a u' - u a') / g^3 with u' = 2m,
 * a' = -2m (u + u^3/2): D g^2 = g^3 - z 2m (1 + u^2/2 + 3u^4/8); scaled by g^2,
 * (along, across) = (g^2, D g^2). */
FF_INLINE BendSample bend_sample_paper(float x, float z, float m) {
  const float u = clamp(2.0f * m * x, -1.0f, 1.0f);
  const float u2 = u * u;
  const float a = 1.0f - u2 * (0.5f + 0.125f * u2);
  const float g2 = a * a + u2;
  const float inverse_g = rsqrt(g2);
  const float g = g2 * inverse_g;
  BendSample s;
  s.spine_x = x * (1.0f - u2 * (1.0f / 6.0f + u2 * (1.0f / 40.0f)));
  s.spine_z = 0.5f * u * x; /* m x^2 */
  s.sin_t = u * inverse_g;
  s.cos_t = a * inverse_g;
  s.along = g2;
  s.across = g2 * g - z * 2.0f * m * (1.0f + u2 * (0.5f + 0.375f * u2));
  return s;
}

/* The bend chosen by FF_BEND_EXACT, for kernels specialised to one mode. */
FF_INLINE BendSample bend_sample(float x, float z, float m) {
#if FF_BEND_EXACT
  return bend_sample_exact(x, z, m);
#else
  return bend_sample_paper(x, z, m);
#endif
}

/* sin(h) / h and cos(h) for |h| <= pi/2 by their Taylor series to h^12 (truncation
 * below 1e-8): no calls and no branches, so it vectorises. */
FF_INLINE float sin_over_h(float h) {
  const float q = h * h;
  return 1.0f + q * (-1.0f / 6.0f + q * (1.0f / 120.0f + q * (-1.0f / 5040.0f +
         q * (1.0f / 362880.0f + q * (-1.0f / 39916800.0f + q * (1.0f / 6227020800.0f))))));
}

FF_INLINE float cos_of_h(float h) {
  const float q = h * h;
  return 1.0f + q * (-0.5f + q * (1.0f / 24.0f + q * (-1.0f / 720.0f +
         q * (1.0f / 40320.0f + q * (-1.0f / 3628800.0f + q * (1.0f / 479001600.0f))))));
}

/* Hinge (METHOD.md section 6, the general inextensible spine): the spine's angle
 * theta(x) ramps linearly from 0 at x = 0 to `angle` at x = width (a step at 0 when
 * width = 0), |angle| <= pi. x < 0 is untouched; the ramp bends into a circular arc
 * (no crease); beyond it the part is rigidly rotated about e_y:
 *   X = min(x, 0) + r sin(theta)/theta + b cos(theta),
 *   Z =             r (1 - cos(theta))/theta + b sin(theta),
 * r = clamp(x, 0, width), b = max(x - width, 0), theta = angle r / width (angle past
 * the ramp). With h = theta / 2: sin(theta)/theta = (sin h / h) cos h and
 * (1 - cos theta)/theta = (sin h / h) sin h. Curvature k = angle / width inside the
 * ramp, 0 elsewhere: (along, across) = (1, 1 - z k). inverse_width = 1 / width
 * (any value when width = 0), from the host: no division per vertex. */
FF_INLINE BendSample hinge_sample(float x, float z, float angle, float width,
                                  float inverse_width) {
  const int has_ramp = width > 0.0f;
  const float ramp = has_ramp ? clamp(x, 0.0f, width) : 0.0f;
  const float beyond = fmax(x - width, 0.0f);
  const float fraction = has_ramp ? ramp * inverse_width : (x > 0.0f ? 1.0f : 0.0f);
  const float half_theta = 0.5f * angle * fraction;
  const float sinc_h = sin_over_h(half_theta);
  const float sin_h = sinc_h * half_theta;
  const float cos_h = cos_of_h(half_theta);
  BendSample s;
  s.sin_t = 2.0f * sin_h * cos_h;
  s.cos_t = 1.0f - 2.0f * sin_h * sin_h;
  s.spine_x = fmin(x, 0.0f) + ramp * sinc_h * cos_h + beyond * s.cos_t;
  s.spine_z = ramp * sinc_h * sin_h + beyond * s.sin_t;
  const int in_ramp = has_ramp & (x > 0.0f) & (x < width);
  s.along = 1.0f;
  s.across = 1.0f - z * (in_ramp ? angle * inverse_width : 0.0f);
  return s;
}

/* Vectors are plain structs of scalars, not float3: once inlined they dissolve into
 * scalar registers, which lets PoCL vectorise across work-items (float3 operations
 * keep its loop vectoriser from doing so). Two unused floats make the struct larger
 * than 16 bytes: PoCL compiles for the host's calling convention, which passes
 * structs of up to 16 bytes as 2-float vectors, and such vectors, once formed, also
 * stop the vectoriser; larger structs dissolve into scalars. */
typedef struct {
  float x, y, z;
  float unused0, unused1;
} Vec3;

FF_INLINE Vec3 vec3(float x, float y, float z) {
  Vec3 v = {x, y, z, 0.0f, 0.0f};
  return v;
}

/* v / |v| without the library normalize()'s branches for huge and tiny vectors:
 * rest normals are unit and the bend keeps them of order 1. */
FF_INLINE Vec3 unit(Vec3 v) {
  const float inverse_length = rsqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return vec3(v.x * inverse_length, v.y * inverse_length, v.z * inverse_length);
}

/* (7): p' = f(x, y, 0) + z n. */
FF_INLINE Vec3 bend_position(Vec3 p, BendSample s) {
  return vec3(s.spine_x - p.z * s.sin_t, p.y, s.spine_z + p.z * s.cos_t);
}

/* R v: the rotation about e_y taking e_z to n = (-sin_t, 0, cos_t). */
FF_INLINE Vec3 rotate_to_secant_normal(Vec3 v, BendSample s) {
  return vec3(s.cos_t * v.x - s.sin_t * v.z, v.y, s.sin_t * v.x + s.cos_t * v.z);
}

/* A direction through the bend: rotated by (8), after the Jacobian's weights in
 * Jacobian mode (normals: (along, across, across); tangents: (across, along, along)).
 * Rotate mode: (8) is a rotation ((sin_t, cos_t) is a unit vector) and rest directions
 * are unit, so the result is unit to float rounding and is not renormalised; the
 * weights scale, so Jacobian mode renormalises. */
FF_INLINE Vec3 bend_direction(Vec3 v, BendSample s, float weight_x, float weight_yz) {
#if FF_NORMALS_JACOBIAN
  return unit(rotate_to_secant_normal(vec3(weight_x * v.x, weight_yz * v.y, weight_yz * v.z), s));
#else
  return rotate_to_secant_normal(v, s);
#endif
}

FF_INLINE Vec3 bend_normal(Vec3 n, BendSample s) { return bend_direction(n, s, s.along, s.across); }

FF_INLINE Vec3 bend_tangent(Vec3 t, BendSample s) { return bend_direction(t, s, s.across, s.along); }

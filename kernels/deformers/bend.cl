/* The paper's fish bend (METHOD.md section 5): the spine becomes z = m x^2 while
 * keeping its arc length, in the paper's 4th-order series (15)-(17) or the exact
 * closed form. Registry entry: engine/src/rig/deformers/bend.cpp.
 *
 * Everything is written with u = 2 m x, the slope of the bent spine z = m x^2.
 * Valid range (13): |m| <= 0.5 / x_max, so u lies in [-1, 1]; u is clamped there so
 * float rounding at the limit cannot produce NaN.
 *
 * Build option FF_BEND_EXACT (the single-bend kernel only; rig kernels call both
 * forms by name): 0, the paper's series; 1, the closed form. */
#ifndef FF_BEND_EXACT
#define FF_BEND_EXACT 0
#endif

/* Floor on sqrt(1 - u^2) where the exact bend's curvature 2m / sqrt(1 - u^2) is
 * infinite; the CPU reference uses the same floor. */
#define FF_MIN_SPINE_COSINE 1e-6f

/* asin(u) / u for u in [-1, 1], without branches and without the 0/0 at u = 0, so the
 * exact bend vectorises and is smooth through m = 0. Cephes' asinf: for |u| <= 1/2,
 * asin(u) = u + u z P(z) with z = u^2, so asin(u)/u = 1 + z P(z); for |u| > 1/2,
 * asin(|u|) = pi/2 - 2 asin(sqrt(z)) with z = (1 - |u|)/2. Relative error 2.5e-7. */
FF_INLINE LaneFloat asin_over_u(LaneFloat u) {
  const LaneFloat a = fabs(u);
  const LaneMask big = a > 0.5f;
  const LaneFloat z = big ? 0.5f * (1.0f - a) : a * a;
  const LaneFloat root = sqrt(z);
  const LaneFloat p = ((((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z +
                    7.4953002686e-2f) * z + 1.6666752422e-1f) * z;
  const LaneFloat small_ratio = 1.0f + p;                               /* |u| <= 1/2 */
  const LaneFloat big_ratio = (M_PI_2_F - 2.0f * (root + root * p)) / fmax(a, 0.5f);
  return big ? big_ratio : small_ratio;
}

/* Exact bend: x' = x sqrt(1 - u^2) / 2 + asin(u) / (4m) = x (c + asin(u) / u) / 2;
 * (1 - u)(1 + u) keeps c accurate as |u| -> 1. |df/dx| = 1, k = 2m / c: scaled by c,
 * (along, across) = (c, c - 2 m z). */
FF_INLINE SecantSample bend_sample_exact(LaneFloat x, LaneFloat z, float m) {
  const LaneFloat u = clamp(2.0f * m * x, -1.0f, 1.0f);
  const LaneFloat c = sqrt((1.0f - u) * (1.0f + u));
  const LaneFloat c_floor = fmax(c, FF_MIN_SPINE_COSINE);
  SecantSample s;
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
FF_INLINE SecantSample bend_sample_paper(LaneFloat x, LaneFloat z, float m) {
  const LaneFloat u = clamp(2.0f * m * x, -1.0f, 1.0f);
  const LaneFloat u2 = u * u;
  const LaneFloat a = 1.0f - u2 * (0.5f + 0.125f * u2);
  const LaneFloat g2 = a * a + u2;
  const LaneFloat inverse_g = rsqrt(g2);
  const LaneFloat g = g2 * inverse_g;
  SecantSample s;
  s.spine_x = x * (1.0f - u2 * (1.0f / 6.0f + u2 * (1.0f / 40.0f)));
  s.spine_z = 0.5f * u * x; /* m x^2 */
  s.sin_t = u * inverse_g;
  s.cos_t = a * inverse_g;
  s.along = g2;
  s.across = g2 * g - z * 2.0f * m * (1.0f + u2 * (0.5f + 0.375f * u2));
  return s;
}

/* The bend chosen by FF_BEND_EXACT, for kernels specialised to one mode. */
FF_INLINE SecantSample bend_sample(LaneFloat x, LaneFloat z, float m) {
#if FF_BEND_EXACT
  return bend_sample_exact(x, z, m);
#else
  return bend_sample_paper(x, z, m);
#endif
}

/* Stage functions (kernels/common/stage_frame.cl): values[0] is m. */
FF_INLINE SecantSample bend_paper_stage(Vec3 p, StageFrame f, __global const float* values,
                                        __global const float* derived) {
  return bend_sample_paper(p.x, p.z, values[0]);
}

FF_INLINE SecantSample bend_exact_stage(Vec3 p, StageFrame f, __global const float* values,
                                        __global const float* derived) {
  return bend_sample_exact(p.x, p.z, values[0]);
}

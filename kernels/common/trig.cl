/* Sines and cosines without calls and without branches, so that the kernels that use
 * them vectorise (PoCL's work-group vectoriser stops at a call to sin or cos). Build
 * option FF_NATIVE_TRIG (the host's, engine/src/device_profile.hpp): 1 where the
 * kernels may take the hardware's native_sin and native_cos instead. */
#ifndef FF_NATIVE_TRIG
#define FF_NATIVE_TRIG 0
#endif

/* sin(h) / h and cos(h) for |h| <= pi/2 as polynomials in q = h^2, with no calls and
 * no branches, so they vectorise. Their coefficients minimise the largest error over
 * |h| <= pi/2 (a minimax fit, not the Taylor series: as exact with fewer terms), the
 * constant held at 1 so that h = 0 gives exactly 1 (identity at zero parameters):
 * sin(h)/h to q^4, error below 5e-9, cos(h) to q^5, below 3e-10, before float32
 * rounding; evaluated in float32, both within 9e-8 of the true values, as the
 * Taylor series to h^12 were with two and one more terms. */
FF_INLINE LaneFloat sin_over_h(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-1.666666046e-01f + q * (8.333088167e-03f +
         q * (-1.981111271e-04f + q * 2.608932569e-06f)));
}

FF_INLINE LaneFloat cos_of_h(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-4.999999955e-01f + q * (4.166664073e-02f + q * (-1.388840351e-03f +
         q * (2.476188620e-05f + q * -2.607710452e-07f))));
}

/* sin(a) and cos(a) for |a| <= pi, from the half angle h = a / 2 (|h| <= pi/2):
 * sin a = 2 sin h cos h, cos a = 1 - 2 sin^2 h; |error| below 2.5e-7 and 7e-7 (the
 * float32 rounding of 1 - 2 sin^2 h, largest near a = +-pi). Of one value
 * (per instance, not per vertex): one-lane programs only. */
#if FF_LANES == 1
FF_INLINE void sin_cos(float a, float* s, float* c) {
  const float h = 0.5f * clamp(a, -M_PI_F, M_PI_F);
  const float sin_h = h * sin_over_h(h);
  *s = 2.0f * sin_h * cos_of_h(h);
  *c = 1.0f - 2.0f * sin_h * sin_h;
}
#endif

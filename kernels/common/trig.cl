/* Sines and cosines without calls and without branches, so that the kernels that use
 * them vectorise (PoCL's work-group vectoriser stops at a call to sin or cos). Build
 * option FF_NATIVE_TRIG (the host's, engine/src/device_profile.hpp): 1 where the
 * kernels may take the hardware's native_sin and native_cos instead. */
#ifndef FF_NATIVE_TRIG
#define FF_NATIVE_TRIG 0
#endif

/* sin(h) / h and cos(h) for |h| <= pi/2 by their Taylor series to h^12 (truncation
 * below 1e-8): no calls and no branches, so it vectorises. */
FF_INLINE LaneFloat sin_over_h(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-1.0f / 6.0f + q * (1.0f / 120.0f + q * (-1.0f / 5040.0f +
         q * (1.0f / 362880.0f + q * (-1.0f / 39916800.0f + q * (1.0f / 6227020800.0f))))));
}

FF_INLINE LaneFloat cos_of_h(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-0.5f + q * (1.0f / 24.0f + q * (-1.0f / 720.0f +
         q * (1.0f / 40320.0f + q * (-1.0f / 3628800.0f + q * (1.0f / 479001600.0f))))));
}

/* sin(a) and cos(a) for |a| <= pi, from the half angle h = a / 2 (|h| <= pi/2):
 * sin a = 2 sin h cos h, cos a = 1 - 2 sin^2 h; |error| below 1e-7. Of one value
 * (per instance, not per vertex): one-lane programs only. */
#if FF_LANES == 1
FF_INLINE void sin_cos(float a, float* s, float* c) {
  const float h = 0.5f * clamp(a, -M_PI_F, M_PI_F);
  const float sin_h = h * sin_over_h(h);
  *s = 2.0f * sin_h * cos_of_h(h);
  *c = 1.0f - 2.0f * sin_h * sin_h;
}
#endif

/* Sines, cosines and an arctangent without calls and without branches, so that the
 * kernels that use them vectorise (PoCL's work-group vectoriser stops at a call to
 * sin, cos or atan: the swim driver took 1.33 ms a frame for 1,000 fish on 2 cores with
 * them, 0.2 ms without). Build
 * option FF_NATIVE_TRIG (the host's, engine/src/cl/device_profile.hpp): 1 where the
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

/* The same for |h| <= FF_GENTLE_HALF_TURN only, two terms after the constant (minimax over
 * that range, the constant held at 1): errors below 1.9e-9 and 1.3e-8 before float32
 * rounding, within 3.3e-8 and 4.6e-8 of the true values in float32, as close as the
 * polynomials above. A spine's segment that turns by at most 0.5 rad, as the segments
 * of a swimming fish do, and a hinge folded by at most 0.5 rad take them on CPUs
 * (kernels/deformers/spine.cl, hinge.cl): five multiply-adds fewer a vertex. */
#define FF_GENTLE_HALF_TURN 0.25f

FF_INLINE LaneFloat sin_over_h_gentle(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-1.666663333e-01f + q * 8.316085550e-03f);
}

FF_INLINE LaneFloat cos_of_h_gentle(LaneFloat h) {
  const LaneFloat q = h * h;
  return 1.0f + q * (-4.999976672e-01f + q * 4.154596686e-02f);
}

/* sin(h) / h and cos(h) by the short polynomials where `gentle` (|h| <=
 * FF_GENTLE_HALF_TURN known for every lane: one branch for the work-item), else by the
 * long ones. */
FF_INLINE void sinc_and_cos(LaneFloat h, int gentle, LaneFloat* sinc_h, LaneFloat* cos_h) {
  if (gentle) {
    *sinc_h = sin_over_h_gentle(h);
    *cos_h = cos_of_h_gentle(h);
  } else {
    *sinc_h = sin_over_h(h);
    *cos_h = cos_of_h(h);
  }
}

/* sin(a) and cos(a) for |a| <= pi, from the half angle h = a / 2 (|h| <= pi/2):
 * sin a = 2 sin h cos h, cos a = 1 - 2 sin^2 h; |error| below 2.5e-7 and 7e-7 (the
 * float32 rounding of 1 - 2 sin^2 h, largest near a = +-pi). These and the functions
 * below take lane values (common/lanes.cl): in a program of more than one lane each
 * lane is an instance's own angle (the swim driver's fish on CPUs). */
FF_INLINE void sin_cos(LaneFloat a, LaneFloat* s, LaneFloat* c) {
  const LaneFloat h = 0.5f * clamp(a, -M_PI_F, M_PI_F);
  const LaneFloat sin_h = h * sin_over_h(h);
  *s = 2.0f * sin_h * cos_of_h(h);
  *c = 1.0f - 2.0f * sin_h * sin_h;
}

/* sin and cos of 2 pi turns, for any turns: the whole turns taken off exactly (to
 * [-1/2, 1/2]), then sin_cos. */
FF_INLINE void sin_cos_turns(LaneFloat turns, LaneFloat* s, LaneFloat* c) {
  const LaneFloat within = turns - floor(turns + 0.5f);
  sin_cos(2.0f * M_PI_F * within, s, c);
}

/* sin(a) and cos(a) for an angle a in radians: a - 2 pi k in three parts (Cody and
 * Waite: 2 pi = 6.28125 + 1.93500518798828125e-3 + 3.01991598e-7, the first two with
 * few significant bits, so that k times them is exact), then sin_cos. The reduction
 * is exact to float rounding while |a| < 8192. */
FF_INLINE void sin_cos_radians(LaneFloat a, LaneFloat* s, LaneFloat* c) {
  const LaneFloat k = floor(a * (0.5f / M_PI_F) + 0.5f);
  const LaneFloat within = ((a - k * 6.28125f) - k * 1.93500518798828125e-3f) - k * 3.01991598e-7f;
  sin_cos(within, s, c);
}

/* atan(x) for any x, without calls: t = min(|x|, 1/|x|) in [0, 1] (atan |x| =
 * pi/2 - atan t when |x| > 1), and above tan(pi/8), u = (t - 1) / (t + 1) (atan t =
 * pi/4 + atan u), so |u| <= tan(pi/8); there atan(u) = u (1 + q P(q)), q = u^2, P a
 * minimax fit of degree 3 (error below 1e-9 before float32 rounding; in float32
 * within 1.4e-7 of atan over all x). */
FF_INLINE LaneFloat arctan(LaneFloat x) {
  const LaneFloat a = fabs(x);
  const LaneMask inverted = a > 1.0f;
  const LaneFloat t = inverted ? 1.0f / fmax(a, 1.0f) : a;
  const LaneMask shifted = t > 0.41421356f;
  const LaneFloat u = shifted ? (t - 1.0f) / (t + 1.0f) : t;
  const LaneFloat q = u * u;
  const LaneFloat p = -3.333295525e-01f + q * (1.997792603e-01f +
                      q * (-1.387984938e-01f + q * 8.060306961e-02f));
  LaneFloat r = u + u * q * p;
  r = shifted ? r + M_PI_4_F : r;
  r = inverted ? M_PI_2_F - r : r;
  return x < 0.0f ? -r : r;
}

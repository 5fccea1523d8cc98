/* The general inextensible spine (METHOD.md section 6): per instance a table of
 * tangent angles theta_k at `samples` points x_k evenly spaced over the stage's extent
 * in x, theta linear in between and constant beyond the ends. The spine is
 *   X(x) = integral_0^x cos theta,  Z(x) = integral_0^x sin theta,
 * so it keeps its arc length exactly at any angle, x = 0 (the pivot) staying fixed;
 * n = (-sin theta, 0, cos theta), curvature k = theta'(x). The paper's bend is the case
 * theta = asin(2 m x). Registry entry: engine/src/deformers/spine.cpp.
 *
 * Over one segment, with theta linear (slope a) from theta_j, the integrals are closed
 * forms: integral_0^d cos(theta_j + a t) dt = d cos(theta_j + a d / 2) sinc(a d / 2),
 * and the same with sin (sinc(u) = sin(u) / u). The running integrals at the samples,
 * X_k and Z_k (from x = 0), are the stage's derived values, written by spine_prepare
 * once per instance and frame: a vertex then integrates only its own segment.
 *
 * Stage table constants (DeformerType::stage_constants): 0 x_0 (the first sample),
 * 1 1 / h, 2 h (the spacing), 3 samples - 1. Derived values: X_0..X_{n-1},
 * Z_0..Z_{n-1}, sin theta_0..sin theta_{n-1}, cos theta_0..cos theta_{n-1}. */

/* Trigonometry from kernels/common/trig.cl (no calls: the kernel vectorises). Angles
 * stay within [-pi, pi] (the values' limit); half a segment's turn within pi/2, where
 * sin_over_h holds, as long as no segment turns by more than pi. */

/* The spine at x of a vertex at height z: theta (the angles), derived (X_k, Z_k,
 * sin theta_k, cos theta_k). Within a segment theta = theta_j + 2 delta at its far
 * end, delta = half the turn so far: the sines and cosines at the middle and at the
 * end come from those of theta_j (a table) and of delta (short series) by the
 * angle-addition formulas, the cheapest way on every device. */
FF_INLINE SecantSample spine_sample(float x, float z, __global const float* theta,
                                    __global const float* derived, StageFrame f) {
  const float x_first = FF_STAGE_CONSTANT(f, 0);
  const float inverse_h = FF_STAGE_CONSTANT(f, 1);
  const float h = FF_STAGE_CONSTANT(f, 2);
  const float last = FF_STAGE_CONSTANT(f, 3);
  const float position = (x - x_first) * inverse_h;
  const float segment = clamp(floor(position), 0.0f, last - 1.0f);
  const int j = (int)segment;
  const int count = (int)last + 1;
  const float d = (position - segment) * h;  /* from x_j; outside the table: < 0 or > h */
  const float inside = clamp(d, 0.0f, h);     /* the part of d where theta is linear */
  const float beyond = d - inside;            /* beyond the ends theta is constant */
  const float slope = (theta[j + 1] - theta[j]) * inverse_h;
  const float delta = 0.5f * slope * inside;
  const float sinc_delta = sin_over_h(delta);
  const float sin_delta = delta * sinc_delta;
  const float cos_delta = cos_of_h(delta);
  const float sin_j = derived[2 * count + j];
  const float cos_j = derived[3 * count + j];
  /* theta_j + delta (the chord's direction) and theta_j + 2 delta (the end). */
  const float sin_mid = sin_j * cos_delta + cos_j * sin_delta;
  const float cos_mid = cos_j * cos_delta - sin_j * sin_delta;
  const float sin_two = 2.0f * sin_delta * cos_delta;
  const float cos_two = 1.0f - 2.0f * sin_delta * sin_delta;
  const float sin_end = sin_j * cos_two + cos_j * sin_two;
  const float cos_end = cos_j * cos_two - sin_j * sin_two;
  const float chord = inside * sinc_delta;
  SecantSample s;
  s.spine_x = derived[j] + chord * cos_mid + beyond * cos_end;
  s.spine_z = derived[count + j] + chord * sin_mid + beyond * sin_end;
  s.sin_t = sin_end;
  s.cos_t = cos_end;
  /* |df/dx| = 1; k = slope within the table, 0 beyond it (METHOD.md section 6). */
  s.along = 1.0f;
  s.across = 1.0f - z * (beyond == 0.0f ? slope : 0.0f);
  return s;
}

/* Stage function (kernels/common/stage_frame.cl): values are the angles. */
FF_INLINE SecantSample spine_stage(Vec3 p, StageFrame f, __global const float* values,
                                   __global const float* derived) {
  return spine_sample(p.x, p.z, values, derived, f);
}

/* The running integrals X_k, Z_k of one instance's angles, from x = 0, and sin theta_k,
 * cos theta_k (rig_prepare). */
FF_INLINE void spine_prepare(__global const float* theta, __global float* derived, StageFrame f) {
  const float x_first = FF_STAGE_CONSTANT(f, 0);
  const float inverse_h = FF_STAGE_CONSTANT(f, 1);
  const float h = FF_STAGE_CONSTANT(f, 2);
  const int count = (int)FF_STAGE_CONSTANT(f, 3) + 1;
  for (int k = 0; k < count; ++k) {
    float sin_k, cos_k;
    sin_cos(theta[k], &sin_k, &cos_k);
    derived[2 * count + k] = sin_k;
    derived[3 * count + k] = cos_k;
  }
  /* From the first sample... */
  float x_sum = 0.0f, z_sum = 0.0f;
  derived[0] = 0.0f;
  derived[count] = 0.0f;
  for (int j = 0; j + 1 < count; ++j) {
    const float half_turn = 0.5f * (theta[j + 1] - theta[j]);
    const float chord = h * sin_over_h(half_turn);
    float sin_mid, cos_mid;
    sin_cos(theta[j] + half_turn, &sin_mid, &cos_mid);
    x_sum += chord * cos_mid;
    z_sum += chord * sin_mid;
    derived[j + 1] = x_sum;
    derived[count + j + 1] = z_sum;
  }
  /* ...then from x = 0: subtract the integral up to 0 (0 may lie outside the table). */
  const float position = -x_first * inverse_h;
  const float segment = clamp(floor(position), 0.0f, (float)(count - 2));
  const int j = (int)segment;
  const float d = (position - segment) * h;
  const float inside = clamp(d, 0.0f, h);
  const float beyond = d - inside;
  const float slope = (theta[j + 1] - theta[j]) * inverse_h;
  const float half_turn = 0.5f * slope * inside;
  const float chord = inside * sin_over_h(half_turn);
  float sin_mid, cos_mid, sin_end, cos_end;
  sin_cos(theta[j] + half_turn, &sin_mid, &cos_mid);
  sin_cos(theta[j] + 2.0f * half_turn, &sin_end, &cos_end);
  const float x_origin = derived[j] + chord * cos_mid + beyond * cos_end;
  const float z_origin = derived[count + j] + chord * sin_mid + beyond * sin_end;
  for (int k = 0; k < count; ++k) {
    derived[k] -= x_origin;
    derived[count + k] -= z_origin;
  }
}

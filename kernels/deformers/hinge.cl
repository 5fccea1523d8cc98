/* The hinge (METHOD.md section 6, the general inextensible spine with a linear
 * ramp of its angle): a fin folding about its base. Registry entry:
 * engine/src/rig/deformers/hinge.cpp. */

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
FF_INLINE SecantSample hinge_sample(LaneFloat x, LaneFloat z, float angle, float width,
                                  float inverse_width) {
  const LaneMask has_ramp = FF_UNIFORM_MASK(width > 0.0f);
  const LaneFloat ramp = has_ramp ? clamp(x, 0.0f, width) : 0.0f;
  const LaneFloat beyond = fmax(x - width, 0.0f);
  const LaneFloat fraction =
      has_ramp ? ramp * inverse_width : (x > 0.0f ? (LaneFloat)1.0f : (LaneFloat)0.0f);
  const LaneFloat half_theta = 0.5f * angle * fraction;
  /* |half_theta| <= |angle| / 2, the same for every lane (an instance's value): the short
   * polynomials where the fin folds gently (common/trig.cl), on CPUs (as the spine). */
#if FF_LANES > 1
  const int gentle = 0.5f * fabs(angle) <= FF_GENTLE_HALF_TURN;
#else
  const int gentle = 0;
#endif
  LaneFloat sinc_h, cos_h;
  sinc_and_cos(half_theta, gentle, &sinc_h, &cos_h);
  const LaneFloat sin_h = sinc_h * half_theta;
  SecantSample s;
  s.sin_t = 2.0f * sin_h * cos_h;
  s.cos_t = 1.0f - 2.0f * sin_h * sin_h;
  s.spine_x = fmin(x, 0.0f) + ramp * sinc_h * cos_h + beyond * s.cos_t;
  s.spine_z = ramp * sinc_h * sin_h + beyond * s.sin_t;
  const LaneMask in_ramp = has_ramp & (x > 0.0f) & (x < width);
  s.along = 1.0f;
  s.across = 1.0f - z * (in_ramp ? (LaneFloat)(angle * inverse_width) : (LaneFloat)0.0f);
  return s;
}

/* Stage function (kernels/common/stage_frame.cl): values[0] is the angle; the stage
 * table's constants 0 and 1 are the width and 1 / width. */
FF_INLINE SecantSample hinge_stage(Vec3 p, StageFrame f, __global const float* values,
                                   __global const float* derived) {
  return hinge_sample(p.x, p.z, values[0], FF_STAGE_CONSTANT(f, 0), FF_STAGE_CONSTANT(f, 1));
}

/* The secant-surface transform of one vertex in its stage's local frame, shared by
 * every deformer (METHOD.md section 4): a deformer gives the surface at the vertex's x
 * as a SecantSample; (7) moves the position, (8) or the Jacobian the normal and the
 * tangent.
 *
 * Build option FF_NORMALS_JACOBIAN: 0, normals rotated by (8); 1, normals by the
 * Jacobian's cofactor (METHOD.md section 6). */
#ifndef FF_NORMALS_JACOBIAN
#define FF_NORMALS_JACOBIAN 0
#endif

/* The secant surface at one x of the spine.
 *   spine_x, spine_z: f(x, 0) = (x', 0, z'), the bent spine
 *   sin_t, cos_t:     unit secant normal n = (-sin_t, 0, cos_t) (17); the rotation (8)
 *                     taking e_z to n is the rotation about e_y by -theta
 *   along, across:    Jacobian weights. J = R diag(D, 1, 1) with D = |df/dx| (1 - z k),
 *                     k the spine curvature (METHOD.md section 6). Normals go by the
 *                     cofactor R diag(1, D, D), tangents by R diag(D, 1, 1); both are
 *                     renormalised, so any common positive factor may be dropped:
 *                     normal ~ R (along n_x, across n_y, across n_z),
 *                     tangent ~ R (across t_x, along t_y, along t_z). */
typedef struct {
  LaneFloat spine_x, spine_z;
  LaneFloat sin_t, cos_t;
  LaneFloat along, across;
} SecantSample;

/* (7): p' = f(x, y, 0) + z n. */
FF_INLINE Vec3 secant_position(Vec3 p, SecantSample s) {
  return vec3(s.spine_x - p.z * s.sin_t, p.y, s.spine_z + p.z * s.cos_t);
}

/* R v: the rotation about e_y taking e_z to n = (-sin_t, 0, cos_t) (8). */
FF_INLINE Vec3 rotate_to_secant_normal(Vec3 v, SecantSample s) {
  return vec3(s.cos_t * v.x - s.sin_t * v.z, v.y, s.sin_t * v.x + s.cos_t * v.z);
}

/* A direction through the transform: rotated by (8), after the Jacobian's weights in
 * Jacobian mode (normals: (along, across, across); tangents: (across, along, along)).
 * Rotate mode: (8) is a rotation ((sin_t, cos_t) is a unit vector) and rest directions
 * are unit, so the result is unit to float rounding and is not renormalised; the
 * weights scale, so Jacobian mode renormalises. */
FF_INLINE Vec3 secant_direction(Vec3 v, SecantSample s, LaneFloat weight_x,
                                 LaneFloat weight_yz) {
#if FF_NORMALS_JACOBIAN
  return unit(rotate_to_secant_normal(vec3(weight_x * v.x, weight_yz * v.y, weight_yz * v.z), s));
#else
  return rotate_to_secant_normal(v, s);
#endif
}

FF_INLINE Vec3 secant_normal(Vec3 n, SecantSample s) {
  return secant_direction(n, s, s.along, s.across);
}

FF_INLINE Vec3 secant_tangent(Vec3 t, SecantSample s) {
  return secant_direction(t, s, s.across, s.along);
}

/* A stage's local frame (METHOD.md section 3) as the kernels read it, and the way
 * into and out of it by (2). Shared by every program; FF_STAGE_COUNT (the stage
 * table's length) comes from the host, as generated text before the files. */
#ifndef FF_STAGE_COUNT
#define FF_STAGE_COUNT 1u
#endif

/* A stage's frame, in mesh coordinates: 20 values, value c of stage k at
 * stages[c * FF_STAGE_COUNT + k] (stage-interleaved, so no two values of one frame
 * are adjacent: adjacent ones would be packed into 2-vectors by the compiler, and
 * those stop PoCL from vectorising across work-items):
 *   0-2 e_x, 3 1 / s_x, 4-6 e_y, 7 deformer constant 0,
 *   8-10 e_z, 11 the offset of the stage's values in an instance's parameter row,
 *   12-14 origin (the pivot), 15 s_x, 16-18 deformer constants 1-3,
 *   19 the offset of the stage's derived values in an instance's derived row
 * (the constants: DeformerType::stage_constants, e.g. a hinge's width and 1 / width;
 * derived values: DeformerType::derived_count, written by the rig_prepare kernel).
 * A StageFrame points at stage k's first value; FF_AT(f, c) reads value c. The table
 * is written by stage_table() in engine/src/cl/slot_layout.cpp and compiled into the
 * program as the constant array ff_stage_table (stage_table_source()): where a frame's
 * row is known at compile time, which is everywhere but the shared-code dispatch, its
 * values are literals in the instructions, not loads. Measured on the H100, 10,000
 * swimming fish: 0.88 ms a frame against 0.945 with the table in a buffer. */
typedef __constant const float* StageFrame;
#define FF_AT(f, c) (f)[(c) * FF_STAGE_COUNT]
#define FF_STAGE_VALUES(f) ((uint)FF_AT(f, 11))
#define FF_STAGE_DERIVED(f) ((uint)FF_AT(f, 19))
#define FF_STAGE_CONSTANT(f, k) FF_AT(f, (k) == 0 ? 7 : 15 + (k))

FF_INLINE Vec3 rotate_into(Vec3 v, StageFrame f) {
  return vec3(v.x * FF_AT(f, 0) + v.y * FF_AT(f, 1) + v.z * FF_AT(f, 2), v.x * FF_AT(f, 4) + v.y * FF_AT(f, 5) + v.z * FF_AT(f, 6),
              v.x * FF_AT(f, 8) + v.y * FF_AT(f, 9) + v.z * FF_AT(f, 10));
}

FF_INLINE Vec3 rotate_out_of(Vec3 v, StageFrame f) {
  return vec3(v.x * FF_AT(f, 0) + v.y * FF_AT(f, 4) + v.z * FF_AT(f, 8), v.x * FF_AT(f, 1) + v.y * FF_AT(f, 5) + v.z * FF_AT(f, 9),
              v.x * FF_AT(f, 2) + v.y * FF_AT(f, 6) + v.z * FF_AT(f, 10));
}

/* (2) going in: p = R (p_b - origin) / s_x (normals: R n_b). */
FF_INLINE Vec3 point_into(Vec3 p, StageFrame f) {
  const Vec3 d = rotate_into(vec3(p.x - FF_AT(f, 12), p.y - FF_AT(f, 13), p.z - FF_AT(f, 14)), f);
  return vec3(d.x * FF_AT(f, 3), d.y * FF_AT(f, 3), d.z * FF_AT(f, 3));
}

/* (2) going out: p_b = origin + s_x R^T p (normals: R^T n). */
FF_INLINE Vec3 point_out_of(Vec3 p, StageFrame f) {
  const Vec3 d = rotate_out_of(p, f);
  return vec3(FF_AT(f, 12) + FF_AT(f, 15) * d.x, FF_AT(f, 13) + FF_AT(f, 15) * d.y, FF_AT(f, 14) + FF_AT(f, 15) * d.z);
}

/* Into a stage's frame (2): the vertex (position p, normal n, tangent t) from mesh
 * coordinates to the frame's. The rest planes hold every vertex already in the frame
 * of its first stage (the host transforms them once), so a vertex enters a frame here
 * only for its later stages. */
FF_INLINE void enter_frame(Vec3* p, Vec3* n, Vec3* t, StageFrame f) {
  *p = point_into(*p, f);
  *n = rotate_into(*n, f);
  *t = rotate_into(*t, f);
}

/* A deformer's stage function (DeformerType::cl_function) gives its secant surface at
 * the vertex, in the stage's frame:
 *   SecantSample <name>(Vec3 p, StageFrame f, __global const float* values,
 *                       __global const float* derived)
 * (values: the stage's values of the instance's parameter row; derived: its derived
 * values, for deformers that have them). The shared code applies it, (7) and (8) or the
 * Jacobian, and leaves the frame: to mesh coordinates (leave_frame), or, at the last
 * stage of a placed instance, straight to the world (kernels/common/placement.cl).
 * The vertex is three separate Vec3 variables, never a struct of structs: copying
 * such a struct makes the compiler move pairs of floats as 2-vectors, which stops PoCL
 * from vectorising across work-items. */
FF_INLINE void leave_frame(Vec3* p, Vec3* n, Vec3* t, StageFrame f, SecantSample s) {
  *p = point_out_of(secant_position(*p, s), f);
  *n = rotate_out_of(secant_normal(*n, s), f);
  *t = rotate_out_of(secant_tangent(*t, s), f);
}

/* From a stage's frame straight into the next stage's, where a fused path has both
 * compiled in: leave_frame and enter_frame composed on the host (link_values() in
 * engine/src/cl/rig_source.cpp), p' = (s_a / s_b) M p + c, d' = M d, M = R_b R_a^T,
 * c = R_b (o_a - o_b) / s_b. A link (21 values of the generated ff_link_table): 0-8
 * (s_a / s_b) M, 9-11 c, 12-20 M, row-major. Half the arithmetic of the two transforms
 * (a fin's vertices on their way into the body's spine). */
typedef __constant const float* FrameLink;

FF_INLINE Vec3 link_linear(Vec3 v, FrameLink l) {
  return vec3(v.x * l[0] + v.y * l[1] + v.z * l[2], v.x * l[3] + v.y * l[4] + v.z * l[5],
              v.x * l[6] + v.y * l[7] + v.z * l[8]);
}

FF_INLINE void leave_into(Vec3* p, Vec3* n, Vec3* t, FrameLink l, SecantSample s) {
  /* c first: three multiply-adds a coordinate. */
  const Vec3 q = secant_position(*p, s);
  *p = vec3(l[9] + q.x * l[0] + q.y * l[1] + q.z * l[2],
            l[10] + q.x * l[3] + q.y * l[4] + q.z * l[5],
            l[11] + q.x * l[6] + q.y * l[7] + q.z * l[8]);
  *n = link_linear(secant_normal(*n, s), l + 12);
  *t = link_linear(secant_tangent(*t, s), l + 12);
}

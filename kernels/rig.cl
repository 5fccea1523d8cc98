/* Rig kernels: the paper's hierarchy (METHOD.md section 2). A vertex goes through its
 * own component's chain of stages, then its parent's, ... up to the root's; each stage
 * works in its own frame (METHOD.md section 3) on positions, normals and tangents in
 * mesh coordinates.
 *
 * Vertices are reordered so each component is a contiguous range of work-groups.
 * Which stages apply to which work-groups is the rig's, so it is generated for each
 * rig (engine/src/rig_program.cpp) as two macros over the stage functions below:
 *   FF_RIG_FUSED_STAGES  the whole bottom-up path of the group's component;
 *   FF_RIG_PASS_STAGES   the one stage pass `pass` applies to the group, if any.
 * Their conditions are on get_group_id(0) and `pass` only, uniform over a work-group,
 * so every branch is straight-line code that PoCL vectorises across work-items.
 *
 * Build options: FF_NORMALS_JACOBIAN (bend.cl), FF_TANGENTS (0/1). */
#ifndef FF_TANGENTS
#define FF_TANGENTS 0
#endif

/* A stage's frame, in mesh coordinates: unit axes, the origin (pivot), s_x.
 *   axis_x.w = 1 / s_x,  axis_y.w = hinge width (in the frame's normalised units),  origin.w = s_x. */
typedef struct {
  float4 axis_x;
  float4 axis_y;
  float4 axis_z;
  float4 origin;
} StageFrame;

typedef struct {
  Vec3 p, n, t;
} Vertex;

inline Vec3 rotate_into(Vec3 v, __constant const StageFrame* f) {
  return vec3(v.x * f->axis_x.x + v.y * f->axis_x.y + v.z * f->axis_x.z,
              v.x * f->axis_y.x + v.y * f->axis_y.y + v.z * f->axis_y.z,
              v.x * f->axis_z.x + v.y * f->axis_z.y + v.z * f->axis_z.z);
}

inline Vec3 rotate_out_of(Vec3 v, __constant const StageFrame* f) {
  return vec3(v.x * f->axis_x.x + v.y * f->axis_y.x + v.z * f->axis_z.x,
              v.x * f->axis_x.y + v.y * f->axis_y.y + v.z * f->axis_z.y,
              v.x * f->axis_x.z + v.y * f->axis_y.z + v.z * f->axis_z.z);
}

/* (2) going in: p = R (p_b - origin) / s_x, n = R n_b. */
inline Vertex into_stage(Vertex v, __constant const StageFrame* f) {
  const float inverse_s = f->axis_x.w;
  const Vec3 d = rotate_into(vec3(v.p.x - f->origin.x, v.p.y - f->origin.y, v.p.z - f->origin.z), f);
  Vertex framed;
  framed.p = vec3(d.x * inverse_s, d.y * inverse_s, d.z * inverse_s);
  framed.n = rotate_into(v.n, f);
  framed.t = rotate_into(v.t, f);
  return framed;
}

/* (2) going out: p_b = origin + s_x R^T p, n_b = R^T n. */
inline Vertex out_of_stage(Vertex framed, __constant const StageFrame* f) {
  const float s = f->origin.w;
  const Vec3 d = rotate_out_of(vec3(framed.p.x * s, framed.p.y * s, framed.p.z * s), f);
  Vertex v;
  v.p = vec3(f->origin.x + d.x, f->origin.y + d.y, f->origin.z + d.z);
  v.n = rotate_out_of(framed.n, f);
  v.t = rotate_out_of(framed.t, f);
  return v;
}

/* (7) and (8) (or the Jacobian) on a vertex already in the stage frame. */
inline Vertex bend_local(Vertex framed, BendSample s) {
  Vertex bent;
  bent.p = bend_position(framed.p, s);
  bent.n = bend_normal(framed.n, s);
  bent.t = bend_tangent(framed.t, s);
  return bent;
}

inline Vertex apply_bend_paper(Vertex v, __constant const StageFrame* f, float m) {
  const Vertex framed = into_stage(v, f);
  return out_of_stage(bend_local(framed, bend_sample_paper(framed.p.x, framed.p.z, m)), f);
}

inline Vertex apply_bend_exact(Vertex v, __constant const StageFrame* f, float m) {
  const Vertex framed = into_stage(v, f);
  return out_of_stage(bend_local(framed, bend_sample_exact(framed.p.x, framed.p.z, m)), f);
}

inline Vertex apply_hinge(Vertex v, __constant const StageFrame* f, float angle) {
  const Vertex framed = into_stage(v, f);
  return out_of_stage(bend_local(framed, hinge_sample(framed.p.x, framed.p.z, angle, f->axis_y.w)), f);
}

inline Vertex load_vertex(__global const float* positions, __global const float* normals,
                          __global const float* tangents, size_t first_plane, size_t stride,
                          size_t v) {
  Vertex x;
  x.p = load_plane3(positions, first_plane, stride, v);
  x.n = load_plane3(normals, first_plane, stride, v);
#if FF_TANGENTS
  x.t = load_plane3(tangents, first_plane, stride, v);
#else
  x.t = vec3(1.0f, 0.0f, 0.0f);
#endif
  return x;
}

inline void store_vertex(__global float* positions, __global float* normals,
                         __global float* tangents, size_t first_plane, size_t stride, size_t v,
                         Vertex x) {
  store_plane3(positions, first_plane, stride, v, x.p);
  store_plane3(normals, first_plane, stride, v, x.n);
#if FF_TANGENTS
  store_plane3(tangents, first_plane, stride, v, x.t);
#endif
}

/* Fused path: one NDRange (slots, instances); every vertex walks its whole path in
 * registers and is written once. rest_*: one instance's planes; params: param_count
 * values per instance. */
__kernel void rig_fused(__global const float* restrict rest_positions,
                        __global const float* restrict rest_normals,
                        __global const float* restrict rest_tangents,
                        __global const float* restrict params, const uint param_count,
                        __constant const StageFrame* stages,
                        __global float* restrict out_positions,
                        __global float* restrict out_normals,
                        __global float* restrict out_tangents, const uint stride) {
  const size_t v = get_global_id(0);
  const size_t instance = get_global_id(1);
  const uint group = get_group_id(0);
  __global const float* p = params + instance * param_count;
  Vertex x = load_vertex(rest_positions, rest_normals, rest_tangents, 0, stride, v);
  FF_RIG_FUSED_STAGES
  store_vertex(out_positions, out_normals, out_tangents, instance * 3, stride, v, x);
}

/* Multi-pass path: pass `pass` reads every vertex from src (the rest planes for the
 * first pass, src_planes_per_instance = 0; an instance batch after, = 3), applies its
 * stage where it has one, and writes every vertex to dst: ping-pong buffers, as the
 * paper chains vertex-shader passes through stream-out. */
__kernel void rig_pass(const uint pass,
                       __global const float* restrict src_positions,
                       __global const float* restrict src_normals,
                       __global const float* restrict src_tangents,
                       const uint src_planes_per_instance,
                       __global const float* restrict params, const uint param_count,
                       __constant const StageFrame* stages,
                       __global float* restrict dst_positions,
                       __global float* restrict dst_normals,
                       __global float* restrict dst_tangents, const uint stride) {
  const size_t v = get_global_id(0);
  const size_t instance = get_global_id(1);
  const uint group = get_group_id(0);
  __global const float* p = params + instance * param_count;
  Vertex x = load_vertex(src_positions, src_normals, src_tangents,
                         instance * src_planes_per_instance, stride, v);
  FF_RIG_PASS_STAGES
  store_vertex(dst_positions, dst_normals, dst_tangents, instance * 3, stride, v, x);
}

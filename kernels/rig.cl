/* Rig kernels: the paper's hierarchy (METHOD.md section 2). A vertex goes through its
 * own component's chain of stages, then its parent's, ... up to the root's; each stage
 * works in its own frame (METHOD.md section 3) on positions, normals and tangents in
 * mesh coordinates.
 *
 * Vertices are reordered so each component is a contiguous range of work-groups.
 * Which stages apply to which work-groups is the rig's, so it is generated for each
 * rig (engine/src/cl/rig_source.cpp) as macros over the deformers' stage functions
 * (kernels/deformers/; enter_frame before every stage but a vertex's first, then
 * s = <function>(p, f, values + <offset of the stage's values>, ...) and
 * leave_frame, or FF_LEAVE_LAST at the root's last stage):
 *   FF_RIG_FUSED_<r>     the whole bottom-up path of the group's component, for the
 *                        fused kernel rig_fused_<r>; FF_RIG_FUSED_KERNELS defines them
 *                        (kernels of more than one lane: rig_fused_0 alone, over
 *                        every work-group, a branch per component);
 *   FF_RIG_PASS_<q>      the stage pass q applies to the group, if any;
 *   FF_RIG_PASS_KERNELS  FF_DEFINE_RIG_PASS(q) for every pass.
 * Their conditions are on the work-group's index only (FF_GROUP), so every
 * branch is straight-line code that PoCL vectorises across work-items.
 *
 * The kernels' arguments end with the instances' values (params, param_count values
 * each), their derived values (derived_values, derived_count each), their world
 * placements (common/placement.cl; read when FF_PLACEMENT is 1), the outputs and, with
 * FF_INSTANCE_LIST, the list of the instances to deform (common/instance_list.cl: input
 * `source`, output row `instance`).
 * A placed vertex leaves the root's last stage straight for the world, so placing
 * costs no extra transform (FF_PLACE_FROM_MESH does it only for a root without
 * stages).
 *
 * Build options: FF_NORMALS_JACOBIAN (common/secant.cl), FF_TANGENTS and
 * FF_INSTANCES_PER_ITEM (common/planes.cl), the outputs' formats and arrangement
 * (common/outputs.cl; scratch sets stay float32 planes), FF_LANES (common/lanes.cl: a
 * work-item deforms FF_LANES consecutive slots, a work-group still 64; FinFlex's planes
 * stored as vectors, kernels/cpu/lane_outputs.cl, other layouts lane by lane). Generated
 * before the files:
 * FF_STAGE_COUNT (the stage table's rows), ff_stage_table (the table itself, a
 * program-scope constant: common/stage_frame.cl), FF_ROOT_FRAME (the root frame's row,
 * when the root has no stage), FF_RIG_GROUP_COUNT and the macros above. */
/* The path table (group_path_table in engine/src/cl/launch_plan.cpp): the stage at
 * position j of the path of the work-group's component. Uniform over a work-group. */
#define FF_PATH_STAGE(j) group_paths[(j) * FF_RIG_GROUP_COUNT + group]
/* Its link rows (FF_PATH_WIDTH rows further): the index in ff_link_table of the link
 * from the stage at position j into the next one (common/stage_frame.cl leave_into). */
#define FF_PATH_LINK(j) group_paths[(FF_PATH_WIDTH + (j)) * FF_RIG_GROUP_COUNT + group]

/* The work-group's index among all the rig's work-groups (a launch may start at an
 * offset), from builtins uniform over a work-group. */
#define FF_GROUP ((uint)(get_group_id(0) + get_global_offset(0) / get_local_size(0)))

/* The work-item's instances (common/instance_list.cl): between these, `instance` (its
 * output row), `source` (its inputs) and its `values` and `derived` values. */
#define FF_BEGIN_RIG_INSTANCES                                                   \
  FF_EACH_INSTANCE_ROW {                                                         \
    for (uint k = 0; k < FF_INSTANCES_PER_ITEM; ++k) {                           \
      const size_t instance = first_instance + k;                                \
      if (instance >= listed) break;                                             \
      FF_SOURCE_OR_SKIP(source)                                                  \
      __global const float* values = params + source * param_count;              \
      __global const float* derived = derived_values + source * derived_count;
#define FF_END_RIG_INSTANCES \
  }                          \
  }

/* Fused path: kernel rig_fused_r covers the work-groups of launch r
 * (engine/src/cl/launch_plan.cpp, make_fused_plan) over (its slots, ceil(instances /
 * FF_INSTANCES_PER_ITEM)); every vertex walks its whole path in registers and is
 * written once, for each of the work-item's instances. rest_*: one instance's planes;
 * params: param_count values per instance. */
#define FF_DEFINE_RIG_FUSED(r)                                                          \
  __kernel void rig_fused_##r(                                                          \
      __global const float* restrict rest_positions,                                    \
      __global const float* restrict rest_normals,                                      \
      __global const float* restrict rest_tangents, __global const float* restrict params, \
      const uint param_count,                                                           \
      __global const uint* restrict group_paths,                                        \
      __global const float* restrict derived_values, const uint derived_count,          \
      __global const float* restrict placements, FF_OUTPUT_ARGUMENTS,                   \
      const uint stride, const uint instances FF_INSTANCE_LIST_ARGUMENTS) {             \
    FF_OUTPUT_LOCALS                                                                    \
    const size_t v = FF_FIRST_SLOT;                                                     \
    const uint group = FF_GROUP;                                                        \
    const Vec3 rest_p = load_plane3(rest_positions, 0, stride, v);                      \
    const Vec3 rest_n = load_plane3(rest_normals, 0, stride, v);                        \
    const Vec3 rest_t = FF_LOAD_TANGENT(rest_tangents, 0, stride, v);                   \
    FF_BEGIN_RIG_INSTANCES                                                              \
    Vec3 p = rest_p, n = rest_n, t = rest_t;                                            \
    FF_RIG_FUSED_##r                                                                    \
    FF_PLACE_FROM_MESH                                                                  \
    FF_STORE_OUTPUTS(instance, v)                                                       \
    FF_END_RIG_INSTANCES                                                                \
  }

FF_RIG_FUSED_KERNELS

/* Multi-pass path: pass q (kernel rig_pass_q) runs the steps engine/src/cl/launch_plan.cpp
 * planned for it (make_pass_plan): for each range of work-groups, load the vertex from
 * the set its previous stage wrote (the rest mesh before its first stage), apply the
 * pass's stage, store it to the outputs if that was its last stage, else to the other
 * float32 scratch set: ping-pong buffers, as the paper chains vertex-shader passes
 * through stream-out, but a pass touches only the vertices it has a stage for.
 * The generated FF_RIG_PASS_q is a chain of
 *   if (group in range) { FF_LOAD_<set> apply_...(...); FF_STORE_<set> }
 * with set one of REST, SCRATCH_A, SCRATCH_B, OUTPUT. One kernel per pass, so each
 * holds only its own branches. */
#define FF_LOAD_SET(prefix, first)                          \
  p = load_plane3(prefix##_positions, first, stride, v);   \
  n = load_plane3(prefix##_normals, first, stride, v);     \
  t = FF_LOAD_TANGENT(prefix##_tangents, first, stride, v);
#define FF_LOAD_REST FF_LOAD_SET(rest, 0)
#define FF_LOAD_SCRATCH_A FF_LOAD_SET(a, instance * 3)
#define FF_LOAD_SCRATCH_B FF_LOAD_SET(b, instance * 3)

#if FF_TANGENTS
#define FF_STORE_SCRATCH_TANGENT(planes, first, v, value) store_plane3(planes, first, stride, v, value)
#else
#define FF_STORE_SCRATCH_TANGENT(planes, first, v, value)
#endif
/* Scratch sets hold float32 normals whatever the output format. */
#define FF_STORE_SCRATCH(prefix)                                        \
  store_plane3(prefix##_positions, instance * 3, stride, v, p);         \
  store_plane3(prefix##_normals, instance * 3, stride, v, n);           \
  FF_STORE_SCRATCH_TANGENT(prefix##_tangents, instance * 3, v, t);
#define FF_STORE_SCRATCH_A FF_STORE_SCRATCH(a)
#define FF_STORE_SCRATCH_B FF_STORE_SCRATCH(b)
#define FF_STORE_OUTPUT \
  FF_PLACE_FROM_MESH    \
  FF_STORE_OUTPUTS(instance, v)

#define FF_DEFINE_RIG_PASS(q)                                                           \
  __kernel void rig_pass_##q(                                                           \
      __global const float* restrict rest_positions,                                    \
      __global const float* restrict rest_normals,                                      \
      __global const float* restrict rest_tangents, __global float* restrict a_positions, \
      __global float* restrict a_normals, __global float* restrict a_tangents,          \
      __global float* restrict b_positions, __global float* restrict b_normals,         \
      __global float* restrict b_tangents, __global const float* restrict params,       \
      const uint param_count,                                                           \
      __global const uint* restrict group_paths,                                        \
      __global const float* restrict derived_values, const uint derived_count,          \
      __global const float* restrict placements, FF_OUTPUT_ARGUMENTS,                   \
      const uint stride, const uint instances FF_INSTANCE_LIST_ARGUMENTS) {             \
    FF_OUTPUT_LOCALS                                                                    \
    const size_t v = FF_FIRST_SLOT;                                                     \
    const uint group = FF_GROUP;                                                        \
    FF_BEGIN_RIG_INSTANCES                                                              \
    Vec3 p, n, t;                                                                       \
    FF_RIG_PASS_##q                                                                     \
    FF_END_RIG_INSTANCES                                                                \
  }

FF_RIG_PASS_KERNELS

/* Derived values (DeformerType::derived_count, e.g. a spine's running integrals):
 * kernel rig_prepare writes them from every instance's values before the deformation
 * kernels run, FF_PREPARE_ITEMS work-items per instance: 1 (a work-group's 64 instances
 * side by side) or a power of two up to 64, a work-group of FF_PREPARE_GROUP_SIZE =
 * FF_PREPARE_ITEMS per instance (a spine's table is then shared out and summed by a
 * scan in local memory; engine/src/cl/device_profile.hpp chooses). The stages that
 * have them are listed in the generated FF_RIG_PREPARE (calls "<prepare
 * function>(values + <offset>, derived + <offset>, stages + <k>, scratch, item);" by
 * every work-item of the instance). Launched only when the rig has such stages,
 * always from the one-lane build of the program (it works on instances, not on
 * vertices). Generated with FF_PREPARE_ITEMS: FF_PREPARE_BARRIER(), a barrier between
 * an instance's work-items (none when it has one). */
#if FF_LANES == 1
/* An instance's scratch floats in local memory. */
#define FF_PREPARE_SCRATCH (2 * FF_PREPARE_ITEMS + 2)

__kernel __attribute__((reqd_work_group_size(FF_PREPARE_GROUP_SIZE, 1, 1))) void rig_prepare(
    __global const float* restrict params, const uint param_count,
    __global float* restrict derived_values, const uint derived_count, const uint instances) {
  __local float scratches[FF_PREPARE_GROUP_SIZE / FF_PREPARE_ITEMS * FF_PREPARE_SCRATCH];
  const size_t instance = get_global_id(0) / FF_PREPARE_ITEMS;
  const int item = (int)(get_local_id(0) % FF_PREPARE_ITEMS);
  /* Past the last instance: a whole instance's work-items (a whole group when it has
   * more than one, so no barrier is left waiting). */
  if (instance >= instances) return;
  __local float* scratch = scratches + get_local_id(0) / FF_PREPARE_ITEMS * FF_PREPARE_SCRATCH;
  __global const float* values = params + instance * param_count;
  __global float* derived = derived_values + instance * derived_count;
  FF_RIG_PREPARE
}
#endif

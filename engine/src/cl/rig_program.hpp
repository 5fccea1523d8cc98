// How a rig runs on a device: its vertices reordered into slots (each component a
// contiguous range of whole work-groups, subtrees contiguous), the stage frames as
// the kernels read them, the passes of the multi-pass path, and the generated
// dispatch macros of kernels/rig.cl.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "finflex/model.hpp"
#include "finflex/rig.hpp"

namespace finflex::detail {

struct SlotLayout {
  std::vector<std::uint32_t> slot_of_vertex;
  std::vector<std::int64_t> vertex_of_slot;  // -1 for padding
  std::vector<std::size_t> first_slot;       // per component, plus the end: size C + 1
  std::size_t slot_count = 0;
};

// Components in rig order (depth-first), each padded to a multiple of group_size. A
// component whose path (its chain, then its ancestors') has a stage that looks
// vertices up in a table along x (a deformer with derived values: the spine's
// segments) has its vertices sorted by x in the first such stage's frame, so
// neighbouring slots read the same table entries (one load for a GPU's warp or a CPU
// work-item's lanes); any other keeps the mesh's order, so a rig without such a stage
// has slot = vertex when it has one component.
SlotLayout make_slot_layout(const Rig& rig, const std::vector<glm::vec3>& positions,
                            std::size_t group_size);

// The rest mesh as the rig kernels read it: one instance's planes over slots (x plane,
// y plane, z plane), each vertex in the frame of its first stage (mesh coordinates for
// components without stages); a component's padding slots repeat its last slot's
// position, with normal e_z and tangent e_x.
struct RestPlanes {
  std::vector<float> positions, normals, tangents;  // tangents empty without them
};
RestPlanes make_rest_planes(const RiggedMesh& model, const SlotLayout& slots);

// The stages in rig order (components depth-first, then chain order): the index a
// stage has in the kernels' stage table.
std::size_t stage_index(const Rig& rig, std::size_t component, std::size_t stage);
std::size_t stage_count(const Rig& rig);

// The stage table of kernels/common/stage_frame.cl: kStageValues values per row,
// row-interleaved (value c of row k at [c * stage_table_rows + k]); a row per stage,
// in rig order, then one for the root's frame (FF_ROOT_FRAME, kernels/common/
// placement.cl).
constexpr std::size_t kStageValues = 20;
std::size_t stage_table_rows(const Rig& rig);
std::vector<float> stage_table(const Rig& rig);
std::string stage_table_source(const Rig& rig);

// Derived values (DeformerType::derived_count) per instance, over all stages, and the
// offset of stage (component, stage)'s in that row (stages in rig order).
std::size_t derived_per_instance(const Rig& rig);
std::size_t derived_offset(const Rig& rig, std::size_t component, std::size_t stage);

// The program's kernel files: the common ones, the deformers the rig uses (each once,
// in registry order), then kernels/rig.cl.
std::vector<std::string> rig_program_files(const Rig& rig);

// The path table of kernels/rig.cl: for work-group g and path position j, the stage
// index of the j-th stage on the path of g's component, at [j * group_count + g]
// (0 past the path's end), then, W = path_table_width(model) rows further, the index
// in frame_links(model) of the link from that stage into the next one (0 at the path's
// last stage). The kernels read their stages and links from it, so components whose
// paths have the same deformers share one branch of code.
std::size_t path_table_width(const RiggedMesh& model);
// The frame links of the fused path (kernels/common/stage_frame.cl leave_into), compiled
// into the program as ff_link_table: every pair of consecutive stages on the
// components' paths (from, to: stage indices), once each, in rig order.
struct FrameLinks {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // link i's stages
  std::vector<std::vector<std::size_t>> of_path;           // component c's link after path stage j
};
FrameLinks frame_links(const RiggedMesh& model);
std::vector<std::uint32_t> group_path_table(const RiggedMesh& model, const SlotLayout& slots,
                                            std::size_t group_size);

// The multi-pass path. Pass q applies the stages at one (depth, chain position),
// deepest first, each to its component's whole subtree. A vertex is read from where its
// previous stage left it (the rest mesh before its first) and written to the outputs by
// its last stage; the stages in between ping-pong between two float32 scratch sets.
// Work-groups a pass has no stage for are not touched, so a vertex moves only as many
// times as it has stages. Components without any stage are copied by pass 0.
enum class PlaneSet { kRest, kScratchA, kScratchB, kOutput };

// One branch of a pass over a range of work-groups: load from `source`, apply the
// stage at `path_position` of each group's path (its deformer's `function`; none: a
// copy), store to `target`. `stage` and `values`: the stage's index and the offset of
// its values in a parameter row, the same for the whole range unless steps share code.
struct PassStep {
  std::size_t first_group = 0;
  std::size_t end_group = 0;
  PlaneSet source = PlaneSet::kRest;
  PlaneSet target = PlaneSet::kOutput;
  const char* function = nullptr;
  std::size_t path_position = 0;
  std::size_t stage = 0;
  std::size_t values = 0;
  std::size_t derived = 0;
};

struct PassPlan {
  std::vector<std::vector<PassStep>> passes;
  std::size_t scratch_sets = 0;  // 0, 1 or 2
  // Vertex records read from or written to scratch sets, over all passes, per slot.
  double scratch_records_per_slot = 0.0;
};
// share_code: contiguous steps alike but for their stages become one branch (stages
// from the path table); otherwise only steps of one stage do.
PassPlan make_pass_plan(const RiggedMesh& model, const SlotLayout& slots, std::size_t group_size,
                        bool share_code);

// The fused path's kernels: each covers a range of work-groups and, within it, a
// branch per component with vertices of its own (`branch_ends`: the end group of each
// branch; its code is the path of `branch_components`). share_code: one kernel for
// each run of components with the same functions along their paths, whose one-lane
// build shares one branch of code (PoCL vectorises straight-line kernels best);
// otherwise one kernel for all (one launch: GPUs).
struct FusedLaunch {
  std::size_t first_group = 0;
  std::size_t end_group = 0;
  std::vector<std::size_t> branch_ends;
  std::vector<std::size_t> branch_components;
};
std::vector<FusedLaunch> make_fused_plan(const RiggedMesh& model, const SlotLayout& slots,
                                         std::size_t group_size, bool share_code);

// The generated macros of kernels/rig.cl for the rig: FF_STAGE_COUNT,
// FF_RIG_GROUP_COUNT, FF_RIG_FUSED_<r> and FF_RIG_FUSED_KERNELS (kernel rig_fused_<r>
// for fused[r]; with share_code and more than one lane, rig_fused_0 alone, over every
// work-group), FF_RIG_PASS_<q> and FF_RIG_PASS_KERNELS, FF_RIG_PREPARE with
// prepare_items_source(prepare_items). share_code: as for make_pass_plan
// (RigDispatch::kByPathShape).
// The generated macros of the table-preparing code (DeformerType::cl_prepare_function,
// kernels/deformers/spine.cl): FF_PREPARE_ITEMS, `items` work-items per instance (a
// power of two up to a work-group), FF_PREPARE_GROUP_SIZE (table_group_size, in
// device_profile.hpp) and FF_PREPARE_BARRIER(), a barrier between them (none for one).
std::string prepare_items_source(std::size_t items);

// `rest`: the rest planes, from which, with `lane_tables` (the deformer's kernels take
// more than one lane), they get tables of their spine segments (segment_tables.hpp;
// kernels/deformers/spine.cl spine_lanes_segment and spine_stage_swept).
std::string rig_dispatch_source(const RiggedMesh& model, const SlotLayout& slots,
                                const RestPlanes& rest, const std::vector<FusedLaunch>& fused,
                                const PassPlan& plan, std::size_t group_size,
                                std::size_t prepare_items, bool share_code, bool lane_tables);

}  // namespace finflex::detail

// Which work-groups run which stages: the path table the kernels read their stages
// and frame links from, the passes of the multi-pass path and the kernels of the fused
// path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "cl/slot_layout.hpp"
#include "finflex/model.hpp"
#include "finflex/rig.hpp"

namespace finflex::detail {

// The deformer's OpenCL function that applies one stage in its frame; for vertices that
// come straight from the rest planes (the stage is first on their path), its rest
// function where it has one (DeformerType::cl_rest_function).
const char* stage_function(const RigStage& stage, bool from_rest);
// The functions along component c's path: its code shape.
std::vector<const char*> path_functions(const RiggedMesh& model, std::size_t c);

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
// build shares one branch of code (PoCL vectorises straight-line kernels best:
// docs/benchmarks.md#choice-dispatch); otherwise one kernel for all (one launch: GPUs).
struct FusedLaunch {
  std::size_t first_group = 0;
  std::size_t end_group = 0;
  std::vector<std::size_t> branch_ends;
  std::vector<std::size_t> branch_components;
};
std::vector<FusedLaunch> make_fused_plan(const RiggedMesh& model, const SlotLayout& slots,
                                         std::size_t group_size, bool share_code);

}  // namespace finflex::detail

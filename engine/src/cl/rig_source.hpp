// A rig's OpenCL program: its kernel files and the generated source before them (the
// stage and link tables as constant arrays, the dispatch macros of kernels/rig.cl).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cl/launch_plan.hpp"
#include "cl/slot_layout.hpp"
#include "finflex/model.hpp"
#include "finflex/rig.hpp"

namespace finflex::detail {

// The program's kernel files: the common ones, the deformers the rig uses (each once,
// in registry order), then kernels/rig.cl.
std::vector<std::string> rig_program_files(const Rig& rig);

// The stage table (stage_table) as the program-scope constant array ff_stage_table
// (kernels/common/stage_frame.cl): a frame's values fold into the instructions that
// use them (docs/benchmarks.md#choice-compiled-tables).
std::string stage_table_source(const Rig& rig);

// The generated macros of the table-preparing code (DeformerType::cl_prepare_function,
// kernels/deformers/spine.cl): FF_PREPARE_ITEMS, `items` work-items per instance (a
// power of two up to a work-group), FF_PREPARE_GROUP_SIZE (table_group_size, in
// device_profile.hpp) and FF_PREPARE_BARRIER(), a barrier between them (none for one).
std::string prepare_items_source(std::size_t items);

// The generated macros of kernels/rig.cl for the rig: FF_STAGE_COUNT,
// FF_RIG_GROUP_COUNT, FF_RIG_FUSED_<r> and FF_RIG_FUSED_KERNELS (kernel rig_fused_<r>
// for fused[r]; with share_code and more than one lane, rig_fused_0 alone, over every
// work-group), FF_RIG_PASS_<q> and FF_RIG_PASS_KERNELS, FF_RIG_PREPARE with
// prepare_items_source(prepare_items). share_code: as for make_pass_plan
// (RigDispatch::kByPathShape). `rest`: the rest planes, from which, with `lane_tables`
// (the deformer's kernels take more than one lane), they get tables of their spine
// segments (segment_tables.hpp; kernels/deformers/spine.cl spine_lanes_segment and
// spine_stage_swept).
std::string rig_dispatch_source(const RiggedMesh& model, const SlotLayout& slots,
                                const RestPlanes& rest, const std::vector<FusedLaunch>& fused,
                                const PassPlan& plan, std::size_t group_size,
                                std::size_t prepare_items, bool share_code, bool lane_tables);

}  // namespace finflex::detail

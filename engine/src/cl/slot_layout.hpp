// A rig's data as its kernels read it: its vertices reordered into slots (each
// component a contiguous range of whole work-groups, subtrees contiguous), the rest
// mesh over those slots, the stage table and the place of each stage's values and
// derived values in an instance's rows.
#pragma once

#include <cstddef>
#include <cstdint>
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

// The offset of the stage's values in a parameter row.
std::size_t values_offset(const Rig& rig, const RigStage& stage);

// The stage table of kernels/common/stage_frame.cl: kStageValues values per row,
// row-interleaved (value c of row k at [c * stage_table_rows + k]); a row per stage,
// in rig order, then one for the root's frame (FF_ROOT_FRAME, kernels/common/
// placement.cl).
constexpr std::size_t kStageValues = 20;
std::size_t stage_table_rows(const Rig& rig);
std::vector<float> stage_table(const Rig& rig);

// Derived values (DeformerType::derived_count) per instance, over all stages, and the
// offset of stage (component, stage)'s in that row (stages in rig order).
std::size_t derived_per_instance(const Rig& rig);
std::size_t derived_offset(const Rig& rig, std::size_t component, std::size_t stage);

}  // namespace finflex::detail

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

#include "finflex/rig.hpp"

namespace finflex::detail {

struct SlotLayout {
  std::vector<std::uint32_t> slot_of_vertex;
  std::vector<std::int64_t> vertex_of_slot;  // -1 for padding
  std::vector<std::size_t> first_slot;       // per component, plus the end: size C + 1
  std::size_t slot_count = 0;
};

// Components in rig order (depth-first), each padded to a multiple of group_size.
SlotLayout make_slot_layout(const Rig& rig, std::size_t vertex_count, std::size_t group_size);

// The stages in rig order (components depth-first, then chain order): the index a
// stage has in the kernels' stage table.
std::size_t stage_index(const Rig& rig, std::size_t component, std::size_t stage);
std::size_t stage_count(const Rig& rig);

// The stage table of kernels/rig.cl: 16 values per stage, stage-interleaved.
std::vector<float> stage_frames(const Rig& rig);

// One pass of the multi-pass path: the (component, stage) pairs it applies, each to
// the component's whole subtree. Passes go deepest level first, then chain position.
using Pass = std::vector<std::pair<std::size_t, std::size_t>>;
std::vector<Pass> make_passes(const Rig& rig);

// Longest bottom-up path (stages) of any component.
std::size_t longest_path(const Rig& rig);

// The generated macros of kernels/rig.cl for the rig: FF_RIG_STAGE_COUNT,
// FF_RIG_FUSED_STAGES, FF_RIG_PASS_<q> and FF_RIG_PASS_KERNELS.
std::string rig_dispatch_source(const Rig& rig, const SlotLayout& slots,
                                const std::vector<Pass>& passes, std::size_t group_size);

}  // namespace finflex::detail

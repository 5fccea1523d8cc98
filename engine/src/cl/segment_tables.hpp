// Which spine segment the lanes of a CPU work-item lie in, found once when the rig
// program is generated instead of every frame (kernels/deformers/spine.cl): a stage
// of DeformerType::rest_segments (the spine) looks each vertex's segment up along x;
// where all of a work-item's lanes share one, the kernel skips finding it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cl/slot_layout.hpp"
#include "finflex/model.hpp"

namespace finflex::detail {

// Per 8 rest slots (slot_count / 8 entries), for components whose path starts with a
// rest_segments stage: the table segment of the entry's first slot (bits 0-11) and
// bits 12, 13 and 14 set where the 8, 16 or 32 slots from it all lie within the table
// in that one segment, computed as the kernel would from the rest planes' x in float;
// else 0 (the kernel finds the segments itself).
std::vector<std::uint32_t> slot_segments(const RiggedMesh& model, const SlotLayout& slots,
                                         const RestPlanes& rest);

// A swept table's bins, over the swept value's range [-limit, limit] (below): the
// parameter's own limit (RigParameter::limit) or kSweptRange, the smaller. 0.8 rad covers
// the fins of a swimming fish (the swim driver folds the caudal fin by up to 0.35 rad,
// the pectorals by 0.5 about their rest: SwimKinematics), in bins of 0.025 rad, across
// which a fin vertex 0.3 body lengths from its hinge moves by a quarter of a
// 32-sample spine's segment. Values beyond the range take the general path.
constexpr std::size_t kSweptBins = 64;
constexpr double kSweptRange = 0.8;

// For components whose path is one stage of one value (a fin's hinge), then a
// rest_segments stage of DeformerType::cl_swept_function (the body's spine): the
// earlier stage moves the vertices along the spine's x as its value changes, so which
// segments they reach depend on that value. Its range is cut into kSweptBins bins; per
// 8 slots of the component and bin, an entry of the lowest segment they reach (bits
// 0-11) and bits 12, 13 and 14 set where the 8, 16 or 32 slots from them stay within
// that segment and the next for every value in the bin, inside the table (0 where they
// do not). `first_entry[c]`: component c's first entry, kNone where
// it has none; `limit[c]` the range's and `mover_values[c]` the offset of the earlier
// stage's value in an instance's row.
struct SweptSegments {
  static constexpr std::size_t kNone = ~std::size_t{0};
  std::vector<std::uint16_t> entries;
  std::vector<std::size_t> first_entry;
  std::vector<double> limit;
  std::vector<std::size_t> mover_values;
};
SweptSegments swept_segments(const RiggedMesh& model, const SlotLayout& slots);

// The arguments a swept function (DeformerType::cl_swept_function) takes after the
// stage function's own for component c, which has entries: ", values[<mover>], <first
// entry less its first slot's / 8 bins>, <limit>f, <bins / (2 limit)>f" (the generated
// path code's `values`: the instance's row).
std::string swept_arguments(const SweptSegments& swept, const SlotLayout& slots, std::size_t c);

// Program-scope constant arrays of both tables, for the kernels of more than one lane
// (`ff_slot_segments`, `ff_swept_segments`): each only when some of its entries mark
// one segment and it is small enough (slot_segments: 2^15 entries, 128 kB); else
// nothing, and the kernels find the segments themselves. `swept` is cleared when its
// table is left out.
std::string segment_tables_source(const std::vector<std::uint32_t>& slot_table,
                                  SweptSegments& swept);

}  // namespace finflex::detail

// The OpenCL backend's tuning, for benchmarks and tests: the knobs a ClDeformer can be
// built with and what it chose. Not part of the installed API, and no promise of
// stability: the defaults (0, kAuto) are the measured choices of each device kind
// (docs/benchmarks.md#measured-choices), and a user never needs to set them.
#pragma once

#include <cstddef>

#include "finflex/cl_deformer.hpp"
#include "finflex/export.hpp"

namespace finflex {

// How the generated rig kernels tell the work-groups' stages apart (every branch is
// uniform over a work-group; docs/benchmarks.md#choice-dispatch).
enum class RigDispatch {
  kAuto,          // kPerComponent on GPUs, kByPathShape on CPUs
  kPerComponent,  // a branch per component, its stages compiled in
  kByPathShape,   // a kernel per run of components with the same deformers along their
                  // paths, stages read from a table (one kernel with a branch per
                  // component for kernels of more than one lane)
};

// How kernels of more than one lane write the outputs
// (docs/benchmarks.md#choice-streaming-stores).
enum class OutputStores {
  kAuto,       // kStreaming where a frame's outputs are larger than the caches could hold
  kPlain,      // ordinary stores through the caches
  kStreaming,  // non-temporal stores: whole lines to memory, none read first
};

struct ClTuning {
  // Instances one work-item deforms; 0: the device's choice
  // (docs/benchmarks.md#choice-gpu-instances-per-item).
  std::size_t instances_per_item = 0;
  RigDispatch dispatch = RigDispatch::kAuto;
  // The whole-body bend on its own kernel; false runs it as a rig (to compare the two).
  bool single_bend_kernel = true;
  // Vertex slots one work-item deforms, one per lane of OpenCL vectors
  // (kernels/common/lanes.cl): 1, 8, 16 or 32 (PoCL only); 0: the device's choice
  // (docs/benchmarks.md#choice-cpu-lanes). internal::lanes() says which layouts take them.
  std::size_t lanes = 0;
  OutputStores stores = OutputStores::kAuto;
  // A vertex struct of float32x3 attributes that fill it (internal/cl_outputs.hpp
  // staged_struct_options) written through local memory as contiguous runs: kAuto
  // stages on GPUs only (docs/benchmarks.md#choice-staged-struct-stores).
  enum class StructStores { kAuto, kStaged, kDirect };
  StructStores struct_stores = StructStores::kAuto;
  // Work-items per instance of the per-instance tables (rig_prepare): 0, or a power of
  // two up to ClDeformer::kGroupSize; 0: the device's choice
  // (docs/benchmarks.md#choice-table-items).
  std::size_t table_items = 0;
};

namespace internal {

// What a deformer chose, for the benchmarks' reports.
// Passes of the multi-pass path: one per (depth, chain position) that has a stage.
FINFLEX_API std::size_t pass_count(const ClDeformer& deformer);
// Float32 vertex records the multi-pass path moves through its scratch sets (reads
// plus writes, all passes), per slot: 0 when no vertex has more than one stage.
FINFLEX_API double scratch_records_per_slot(const ClDeformer& deformer);
// Instances one work-item deforms for `outputs` with normals by `normals`.
FINFLEX_API std::size_t instances_per_item(const ClDeformer& deformer, const OutputLayout& outputs,
                                           NormalMode normals = NormalMode::kRotate);
// Vertex slots one work-item deforms for `outputs` (ClTuning::lanes).
FINFLEX_API std::size_t lanes(const ClDeformer& deformer, const OutputLayout& outputs);
// Whether a frame on `batch` writes it with streaming stores (ClTuning::stores).
FINFLEX_API bool streams_outputs(const ClDeformer& deformer, const DeviceBatch& batch);

// Instances (NDRange rows) a work-group of the kernels of more than one lane covers
// (one-lane kernels: 1; docs/benchmarks.md#choice-lane-group-rows). Rows past the last
// instance are skipped in the kernels.
constexpr std::size_t kLaneGroupRows = 16;
constexpr std::size_t group_rows(std::size_t lanes) { return lanes > 1 ? kLaneGroupRows : 1; }
// The NDRange rows of a launch of `lanes`-lane kernels over `items_high` rows of
// work-items: a whole number of work-groups of group_rows(lanes) rows.
constexpr std::size_t launch_rows(std::size_t items_high, std::size_t lanes) {
  return (items_high + group_rows(lanes) - 1) / group_rows(lanes) * group_rows(lanes);
}

}  // namespace internal
}  // namespace finflex

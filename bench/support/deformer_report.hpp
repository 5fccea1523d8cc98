// What the benchmarks report of a deformer beyond what it deforms: the work-item shape
// of a batch's kernels, the multi-pass path's passes and scratch traffic, and the
// NDRange of the deformation kernels that the reference kernels copy. Every use of
// those ClDeformer members in bench/ and apps/ goes through this file.
#pragma once

#include <cstddef>

#include <CL/opencl.hpp>

#include "finflex/cl_deformer.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::bench {

// How the deformer's kernels cover a batch: instances per work-item, vertex slots per
// work-item (lanes), and whether the outputs are written with streaming stores.
struct KernelShape {
  std::size_t instances_per_item = 1;
  std::size_t lanes = 1;
  bool streaming = false;
};

// The shape of a frame on `batch` with normals by `normals` (ClTuning decides it with
// the device).
KernelShape kernel_shape(const ClDeformer& deformer, const DeviceBatch& batch, NormalMode normals);

// The multi-pass path of a deformer: its passes and the float32 vertex records each slot
// moves through its scratch sets (reads plus writes, all passes). The fused path and the
// single-bend kernel: one pass, none.
struct PassReport {
  std::size_t passes = 1;
  double scratch_records_per_slot = 0.0;
};
PassReport pass_report(const ClDeformer& deformer, RigPath path);

// The deformation kernels' NDRange over `vertices` slots of `instances` instances with
// `per_item` instances and `lanes` slots per work-item: work-groups of
// ClDeformer::kGroupSize slots and their instance rows.
cl::NDRange deformation_global_range(std::size_t vertices, std::size_t instances,
                                     std::size_t per_item, std::size_t lanes);
cl::NDRange deformation_local_range(std::size_t lanes);

}  // namespace finflex::bench

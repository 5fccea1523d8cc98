#include "deformer_report.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::bench {

KernelShape kernel_shape(const ClDeformer& deformer, const DeviceBatch& batch, NormalMode normals) {
  KernelShape shape;
  shape.instances_per_item = internal::instances_per_item(deformer, batch.outputs, normals);
  shape.lanes = internal::lanes(deformer, batch.outputs);
  shape.streaming = internal::streams_outputs(deformer, batch);
  return shape;
}

PassReport pass_report(const ClDeformer& deformer, RigPath path) {
  const RigPath chosen = path == RigPath::kAuto ? deformer.automatic_path() : path;
  PassReport report;
  if (chosen == RigPath::kPasses && !deformer.uses_single_bend_kernel()) {
    report.passes = internal::pass_count(deformer);
    report.scratch_records_per_slot = internal::scratch_records_per_slot(deformer);
  }
  return report;
}

cl::NDRange deformation_global_range(std::size_t vertices, std::size_t instances,
                                     std::size_t per_item, std::size_t lanes) {
  const std::size_t group = ClDeformer::kGroupSize;
  return cl::NDRange((vertices + group - 1) / group * group / lanes,
                     internal::launch_rows((instances + per_item - 1) / per_item, lanes));
}

cl::NDRange deformation_local_range(std::size_t lanes) {
  return cl::NDRange(ClDeformer::kGroupSize / lanes, internal::group_rows(lanes));
}

}  // namespace finflex::bench

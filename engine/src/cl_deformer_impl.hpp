// The OpenCL backend's state for one model (finflex/cl_deformer.hpp): what is uploaded
// once, the kernels by variant, and the per-frame parameter upload and scratch sets.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "device_buffers.hpp"
#include "finflex/cl_deformer.hpp"
#include "kernel_variant.hpp"
#include "parameter_checks.hpp"

namespace finflex {

class ClDeformer::Impl {
 public:
  Impl(Context& context, const RiggedMesh& model, const ClOptions& options);

  // enqueue() and check() of the public class. `checked`: the caller has run check()
  // on this job already (RigFrame), so unclamped values are copied, not checked again.
  cl::Event enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events, bool checked);
  void check(const ClJob& job) const;

  BatchLayout layout(std::size_t instances, NormalFormat format) const;
  std::size_t per_item(NormalFormat format) const;
  std::size_t lanes(NormalFormat format) const;
  bool streams_outputs(const BatchLayout& layout) const;

  Context& context;
  const RiggedMesh model;
  ClOptions options;  // dispatch resolved for the device
  bool single_bend = false;
  std::vector<std::uint32_t> slot_of_vertex;
  std::vector<std::uint32_t> remapped_indices;
  std::size_t pass_count = 0;
  double scratch_records_per_slot = 0.0;
  RigPath automatic_path = RigPath::kFused;

 private:
  // A kernel and what its arguments were last set for: a frame on the same batch with
  // the same deformer buffers is a parameter upload and a launch.
  struct BoundKernel {
    cl::Kernel kernel;
    std::uint64_t batch_serial = 0;
    std::uint64_t generation = 0;
    cl_mem parameters = nullptr;
    cl_mem placements = nullptr;
  };

  // A frame's inputs on the device: the deformer's uploads or the job's own buffers.
  struct FrameInputs {
    const cl::Buffer* parameters = nullptr;
    const cl::Buffer* placements = nullptr;  // a placeholder when the job places nothing
  };

  const detail::ParameterChecker checker_;
  bool tangents_ = false;
  std::size_t slot_count_ = 0;
  cl::Buffer rest_positions_, rest_normals_, rest_tangents_;
  cl::Buffer stages_, group_paths_;
  ProgramSource program_;
  // The single-bend kernel's way back to mesh coordinates: origin, s e_x, s e_y, s e_z,
  // e_x, e_y, e_z of the bend's frame.
  std::array<cl_float4, 7> back_transform_{};
  // The fused path's kernels rig_fused_<r>: the work-groups each covers.
  std::vector<std::pair<std::size_t, std::size_t>> fused_launches_;
  std::size_t scratch_sets_ = 0;

  detail::ParameterUpload upload_;
  detail::ParameterUpload placement_upload_;  // world placement records (16 floats each)
  cl::Buffer no_placements_;                  // the kernels' argument when nothing is placed
  std::vector<cl::Buffer> scratch_;  // 3 per set: positions, normals, tangents
  std::size_t scratch_instances_ = 0;
  // Derived values (DeformerType::derived_count): per instance, written by rig_prepare.
  std::size_t derived_per_instance_ = 0;
  cl::Buffer derived_;
  std::size_t derived_instances_ = 0;
  cl::Kernel prepare_;  // rig_prepare, when the rig has derived values
  // Bumped whenever the parameter buffer or the scratch sets are replaced: kernels set
  // up for an older generation get their arguments again.
  std::uint64_t generation_ = 1;
  std::uint64_t validated_serial_ = 0;
  std::map<detail::KernelVariant, BoundKernel> kernels_;

  // The job's fields, its model and its outputs (not its values).
  void check_shape(const ClJob& job) const;
  void check_outputs(const ClJob& job) const;
  void check_buffer_sizes(const DeviceBatch& batch);
  BoundKernel& kernel(std::size_t index, const ClJob& job);
  void ensure_scratch(std::size_t instances);
  void ensure_derived(std::size_t instances);
  FrameInputs upload_inputs(const ClJob& job, bool checked);
  void prepare_derived(const ClJob& job, const FrameInputs& inputs,
                       std::vector<cl::Event>* kernel_events);
  void launch(BoundKernel& bound, const ClJob& job, std::size_t first_group, std::size_t end_group,
              std::vector<cl::Event>* kernel_events, cl::Event* done);
  void set_arguments(cl::Kernel& kernel, std::size_t index, const ClJob& job,
                     const FrameInputs& inputs) const;
};

}  // namespace finflex

// The OpenCL backend's state for one model (finflex/cl_deformer.hpp): what is uploaded
// once, the kernels by variant, and the per-frame parameter upload and scratch sets.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "cl/device_buffers.hpp"
#include "cl/kernel_variant.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "model/parameter_checks.hpp"

namespace finflex {

class ClDeformer::Impl {
 public:
  Impl(Context& context, const RiggedMesh& model, const ClTuning& tuning);

  // enqueue() and check() of the public class. `checked`: the caller has run check()
  // on this job already (RigFrame), so unclamped values are copied, not checked again.
  // enqueue() holds frame_mutex_ from its checks to its last launch; check() reads
  // only what is fixed at construction.
  cl::Event enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events, bool checked);
  void check(const ClJob& job) const;

  BatchShape shape(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;
  // Instances per work-item for FinFlex's planes in `format` (rotated_planes: with
  // rotated normals), and for `outputs` with `normals`.
  std::size_t per_item(NormalFormat format, bool rotated_planes) const;
  std::size_t per_item(const OutputLayout& outputs, NormalMode normals) const;
  // The outputs' vertex count in `order`: slots, or the mesh's vertices.
  std::size_t output_vertices(VertexOrder order) const;
  // Lanes (ClTuning::lanes), and for a batch's outputs (1 on GPUs unless they are
  // FinFlex's planes); whether outputs are FinFlex's planes (float32 or half normals);
  // streaming stores for a batch.
  std::size_t lanes() const;
  std::size_t lanes(const OutputLayout& outputs) const;
  bool writes_planes(const OutputLayout& outputs) const;
  bool writes_lane_words(const DeviceBatch& batch) const;
  // Whether `outputs` in mesh order are written as slot order without the padding
  // (FF_OUTPUT_LIMIT): the model's slots are its vertices (a plain bend).
  bool writes_mesh_as_slots(const OutputLayout& outputs) const {
    return outputs.order == VertexOrder::kMesh && slots_in_mesh_order_;
  }
  // Whether vertex structs are written through local memory (ClTuning::struct_stores).
  bool stages_structs() const {
    return tuning.struct_stores == ClTuning::StructStores::kStaged ||
           (tuning.struct_stores == ClTuning::StructStores::kAuto &&
            context.description().is_gpu());
  }
  bool streams_outputs(const DeviceBatch& batch) const;
  std::size_t derived_per_instance() const { return derived_per_instance_; }

  Context& context;
  const RiggedMesh model;
  ClTuning tuning;  // dispatch resolved for the device
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
    cl_mem derived = nullptr;
    cl_uint out_layout_argument = 0;  // its index (reset every frame with previous positions)
    cl_uint list_argument = 0;        // the first of a listed job's (set every frame)
  };

  // A frame's inputs on the device: the deformer's uploads or the job's own buffers.
  struct FrameInputs {
    const cl::Buffer* parameters = nullptr;
    const cl::Buffer* placements = nullptr;  // a placeholder when the job places nothing
    const cl::Buffer* derived = nullptr;     // the deformer's (rig_prepare) or the job's
  };

  const detail::ParameterChecker checker_;
  bool tangents_ = false;
  std::size_t slot_count_ = 0;
  bool slots_in_mesh_order_ = true;  // slot s holds mesh vertex s, padding after
  cl::Buffer rest_positions_, rest_normals_, rest_tangents_;
  cl::Buffer group_paths_;
  ProgramSource program_;
  // The single-bend kernel's way back to mesh coordinates: origin, s e_x, s e_y, s e_z,
  // e_x, e_y, e_z of the bend's frame.
  std::array<cl_float4, 7> back_transform_{};
  // The fused path's kernels rig_fused_<r>: the work-groups each covers (with shared
  // code and more than one lane, rig_fused_0 alone covers them all: enqueue).
  std::vector<std::pair<std::size_t, std::size_t>> fused_launches_;
  std::size_t scratch_sets_ = 0;

  // The per-frame state below (staging ring, device parameter buffer, scratch sets,
  // kernels and the arguments they were set up with) belongs to one frame at a time:
  // a frame sets kernel arguments and enqueues its upload and launches under this
  // lock, so frames from several threads reach the in-order queue whole.
  std::mutex frame_mutex_;
  detail::ParameterUpload upload_;
  detail::ParameterUpload placement_upload_;  // world placement records (16 floats each)
  cl::Buffer no_placements_;                  // the kernels' argument when nothing is placed
  std::vector<cl::Buffer> scratch_;           // 3 per set: positions, normals, tangents
  std::size_t scratch_instances_ = 0;
  // Derived values (DeformerType::derived_count): per instance, written by rig_prepare.
  std::size_t derived_per_instance_ = 0;
  cl::Buffer derived_;
  std::size_t derived_instances_ = 0;
  cl::Kernel prepare_;  // rig_prepare, when the rig has derived values
  // Bumped whenever the parameter buffer or the scratch sets are replaced: kernels set
  // up for an older generation get their arguments again.
  std::uint64_t generation_ = 1;
  // What the kernels take from a batch's layout, worked out when the batch is checked.
  struct BatchState {
    std::string options;    // output_build_options() and the rest of its build options
    std::size_t lanes = 1;  // lanes(outputs)
    bool streams = false;   // streams_outputs()
    // per_item(outputs, normals) by normal mode (rotate, Jacobian).
    std::array<std::size_t, 2> per_item = {1, 1};
  };
  // A batch a check passed, as it was then, and its state.
  struct ValidatedBatch {
    std::uint64_t serial = 0;
    OutputLayout outputs;
    std::array<cl_mem, 4> buffers{};
    std::size_t instances = 0;
    BatchState state;
  };
  // The last two batches checked, the latest first: outputs that alternate between two
  // batches (a renderer's two sets of buffers) are checked once each.
  std::array<ValidatedBatch, 2> validated_;
  // The latest batch's state: a frame's kernels take it without working it out again.
  const BatchState& current_batch() const { return validated_[0].state; }
  std::size_t batch_per_item(NormalMode normals) const {
    return current_batch().per_item[normals == NormalMode::kJacobian ? 1 : 0];
  }
  // Per slot its mesh vertex (0xffffffff for padding): outputs in mesh order.
  cl::Buffer vertex_of_slot_;
  std::map<detail::KernelVariant, BoundKernel> kernels_;

  // The job's fields, its model and its outputs (not its values).
  void check_shape(const ClJob& job) const;
  void check_list(const ClJob& job) const;
  void check_outputs(const ClJob& job) const;
  // The instances the frame's inputs hold: the list's sources, else the job's instances.
  static std::size_t input_instances(const ClJob& job) {
    return job.list.entries != nullptr ? job.list.sources : job.instances;
  }
  void check_buffer_sizes(const DeviceBatch& batch);
  BatchState batch_state(const DeviceBatch& batch) const;
  BoundKernel& kernel(std::size_t index, const ClJob& job);
  void ensure_scratch(std::size_t instances);
  void ensure_derived(std::size_t instances);
  void check_derived_buffer(const cl::Buffer& buffer, std::size_t instances) const;
  // The job's derived buffer checked last, and for how many instances.
  cl::Buffer checked_derived_;
  std::size_t checked_derived_instances_ = 0;
  FrameInputs upload_inputs(const ClJob& job, bool checked);
  void prepare_derived(const ClJob& job, const FrameInputs& inputs,
                       std::vector<cl::Event>* kernel_events);
  void launch(BoundKernel& bound, const ClJob& job, std::size_t first_group, std::size_t end_group,
              std::vector<cl::Event>* kernel_events, cl::Event* done);
  // Returns the index of the out_layout argument; *list_argument: the index after the
  // last argument set (where a listed job's begin).
  cl_uint set_arguments(cl::Kernel& kernel, std::size_t index, const ClJob& job,
                        const FrameInputs& inputs, cl_uint* list_argument) const;
  void set_list_arguments(cl::Kernel& kernel, cl_uint first_argument,
                          const ClInstanceList& list) const;
};

}  // namespace finflex

// The OpenCL backend (finflex/cl_deformer.hpp): the model uploaded once; per frame,
// the job checked, its parameters uploaded without blocking, the kernels enqueued.
#include "finflex/cl_deformer.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "cl/deformer_impl.hpp"
#include "cl/device_profile.hpp"
#include "cl/host_pages.hpp"
#include "cl/launch_plan.hpp"
#include "cl/output_buffers.hpp"
#include "cl/output_decoding.hpp"
#include "cl/output_options.hpp"
#include "cl/rig_source.hpp"
#include "cl/slot_layout.hpp"
#include "finflex/error.hpp"
#include "finflex/internal/cl_outputs.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex {
namespace {

using detail::kWorkGroupSize;

cl_float4 to_cl_float4(const glm::dvec3& v) {
  cl_float4 out;
  out.s[0] = static_cast<float>(v.x);
  out.s[1] = static_cast<float>(v.y);
  out.s[2] = static_cast<float>(v.z);
  out.s[3] = 0.0f;
  return out;
}

[[noreturn]] void fail_outputs(const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, "job.outputs", "job.outputs: " + message);
}

// The longest table that rig_prepare shares out (the values of a stage with derived
// values: a spine's samples); 0 when there is none.
std::size_t longest_prepared_table(const Rig& rig) {
  std::size_t longest = 0;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      if (stage.deformer->derived_count == nullptr) continue;
      longest = std::max(longest, rig.parameters[stage.param].count);
    }
  }
  return longest;
}

}  // namespace

// ----------------------------------------------------------------------------------
// Set-up: the model on the device

ClDeformer::Impl::Impl(Context& context_in, const RiggedMesh& model_in, const ClTuning& tuning_in)
    : context(context_in), model(model_in), tuning(tuning_in), checker_(model_in.rig()) {
  const DeviceDescription& device = context.description();
  tuning.dispatch = detail::device_dispatch(device, tuning.dispatch);
  if (tuning.lanes != 0 && tuning.lanes != 1 && tuning.lanes != 8 && tuning.lanes != 16 &&
      tuning.lanes != 32) {
    throw Error(ErrorCode::kInvalidArgument, "tuning.lanes",
                "tuning.lanes: " + std::to_string(tuning.lanes) +
                    " is not a number of lanes (expected 0: the device's, 1, 8, 16 or 32)");
  }
  if (tuning.lanes == 32 && !detail::device_is_pocl(device)) {
    throw Error(ErrorCode::kInvalidArgument, "tuning.lanes",
                "tuning.lanes: 32 lanes are built by PoCL only (a vector type of clang's); "
                "the device's platform is '" +
                    device.platform_name + "' (expected 0, 1, 8 or 16)");
  }
  detail::check_table_items(tuning.table_items, "tuning.table_items");
  tuning.table_items =
      detail::device_table_items(device, longest_prepared_table(model.rig()), tuning.table_items);
  single_bend = tuning.single_bend_kernel && model.is_single_bend();
  const bool share_code = tuning.dispatch == RigDispatch::kByPathShape;
  const Rig& rig = model.rig();
  tangents_ = model.mesh().has_tangents();

  const detail::SlotLayout slots =
      detail::make_slot_layout(rig, model.mesh().positions, kWorkGroupSize);
  slot_count_ = slots.slot_count;
  slot_of_vertex = slots.slot_of_vertex;
  remapped_indices.reserve(model.mesh().indices.size());
  for (std::uint32_t index : model.mesh().indices)
    remapped_indices.push_back(slot_of_vertex[index]);

  const cl::Context& cl_context = context.context();
  std::vector<std::uint32_t> vertex_of_slot(slot_count_);
  for (std::size_t slot = 0; slot < slot_count_; ++slot) {
    const std::int64_t vertex = slots.vertex_of_slot[slot];
    vertex_of_slot[slot] = vertex < 0 ? 0xffffffffu : static_cast<std::uint32_t>(vertex);
    slots_in_mesh_order_ =
        slots_in_mesh_order_ &&
        (slot < model.vertex_count() ? vertex == std::int64_t(slot) : vertex < 0);
  }
  vertex_of_slot_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY,
                                        slot_count_ * sizeof(std::uint32_t), vertex_of_slot.data());
  const detail::RestPlanes rest = detail::make_rest_planes(model, slots);
  const std::size_t plane_bytes = rest.positions.size() * sizeof(float);
  rest_positions_ =
      detail::make_buffer(cl_context, CL_MEM_READ_ONLY, plane_bytes, rest.positions.data());
  rest_normals_ =
      detail::make_buffer(cl_context, CL_MEM_READ_ONLY, plane_bytes, rest.normals.data());
  rest_tangents_ =
      tangents_ ? detail::make_buffer(cl_context, CL_MEM_READ_ONLY,
                                      rest.tangents.size() * sizeof(float), rest.tangents.data())
                : detail::make_buffer(cl_context, CL_MEM_READ_ONLY, sizeof(float));
  no_placements_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, sizeof(float));

  if (single_bend) {
    // The rest planes are in the bend's frame already; the kernel goes back by (2).
    const RigStage& stage = rig.components[0].chain[0];
    const BodyFrame& f = stage.frame;
    back_transform_ = {to_cl_float4(f.origin),
                       to_cl_float4(f.axis_x * f.length),
                       to_cl_float4(f.axis_y * f.length),
                       to_cl_float4(f.axis_z * f.length),
                       to_cl_float4(f.axis_x),
                       to_cl_float4(f.axis_y),
                       to_cl_float4(f.axis_z)};
    std::vector<std::string> files = common_kernel_files();
    files.push_back(stage.deformer->cl_file);
    files.push_back("single_bend.cl");
    const bool exact =
        stage.deformer->cl_function(stage.options) == std::string("bend_exact_stage");
    program_ = {files, std::string("#define FF_BEND_EXACT ") + (exact ? "1" : "0") + "\n", ""};
    fused_launches_.emplace_back(0, slot_count_ / kWorkGroupSize);
    pass_count = 1;
    automatic_path = RigPath::kFused;
    return;
  }

  const std::vector<std::uint32_t> paths = detail::group_path_table(model, slots, kWorkGroupSize);
  group_paths_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY,
                                     paths.size() * sizeof(std::uint32_t), paths.data());
  const detail::PassPlan plan = detail::make_pass_plan(model, slots, kWorkGroupSize, share_code);
  const std::vector<detail::FusedLaunch> fused =
      detail::make_fused_plan(model, slots, kWorkGroupSize, share_code);
  for (const detail::FusedLaunch& launch : fused)
    fused_launches_.emplace_back(launch.first_group, launch.end_group);
  pass_count = plan.passes.size();
  scratch_sets_ = plan.scratch_sets;
  scratch_records_per_slot = plan.scratch_records_per_slot;
  automatic_path =
      model.longest_path() <= ClDeformer::kMaxFusedStages ? RigPath::kFused : RigPath::kPasses;
  program_ = {detail::rig_program_files(rig),
              detail::rig_dispatch_source(model, slots, rest, fused, plan, kWorkGroupSize,
                                          tuning.table_items, share_code, lanes() > 1),
              ""};
  derived_per_instance_ = detail::derived_per_instance(rig);
  // A placeholder until the first frame sizes it: every rig kernel takes the buffer.
  derived_ = detail::make_buffer(cl_context, CL_MEM_READ_WRITE, sizeof(float));
}

BatchShape ClDeformer::Impl::shape(std::size_t instances, NormalFormat format) const {
  BatchShape layout;
  layout.normal_format = format;
  layout.vertex_count = model.vertex_count();
  layout.instance_count = instances;
  layout.plane_stride = slot_count_;
  layout.tangents = tangents_;
  return layout;
}

std::size_t ClDeformer::Impl::per_item(NormalFormat format, bool rotated_planes) const {
  return tuning.instances_per_item
             ? tuning.instances_per_item
             : detail::device_instances_per_item(context.description(), single_bend, format,
                                                 derived_per_instance_ > 0 && rotated_planes);
}

// Normals of fewer than 12 bytes (16-bit and octahedral formats) take the work-item
// shape of half normals. The single-bend kernel writing packed positions (a vertex
// struct or separate arrays) that are not staged through local memory (stages_structs,
// detail::fills_vertex_struct) takes one instance per work-item on GPUs: a warp's
// strided stores then stay within one instance's vertices (the rig's kernels keep their
// usual shape; docs/benchmarks.md#choice-gpu-instances-per-item).
std::size_t ClDeformer::Impl::per_item(const OutputLayout& outputs, NormalMode normals) const {
  const bool staged = stages_structs() && detail::fills_vertex_struct(outputs);
  if (tuning.instances_per_item == 0 && context.description().is_gpu() && single_bend &&
      outputs.positions.arrangement == Arrangement::kPacked && !staged) {
    return 1;
  }
  return per_item(
      format_bytes(outputs.normals.format) < 12 ? NormalFormat::kHalf : NormalFormat::kFloat32,
      writes_planes(outputs) && normals == NormalMode::kRotate);
}

std::size_t ClDeformer::Impl::output_vertices(VertexOrder order) const {
  return order == VertexOrder::kMesh ? model.vertex_count() : slot_count_;
}

std::size_t ClDeformer::Impl::lanes() const {
  return tuning.lanes ? tuning.lanes : detail::device_lanes(context.description());
}

// Lanes store FinFlex's planes (normals float32 or half; previous positions in float32
// planes) and vertex structs in one buffer as vectors (kernels/cpu/lane_outputs.cl) and,
// on CPUs, any other layout lane by lane through the one-slot stores
// (kernels/common/outputs.cl): the arithmetic stays vector code
// (docs/benchmarks.md#choice-cpu-struct-transpose). But the single bend in mesh order
// (but for a struct or arrays of their own, which its lanes store as vectors: its slots
// are its vertices) or with previous positions in another layout: one lane, which
// PoCL's work-group vectoriser makes faster. GPUs: one lane for any layout but the
// planes, whatever ClTuning::lanes asks; and so does a vertex struct staged through
// local memory (ClTuning::struct_stores, a work-item a vertex).
std::size_t ClDeformer::Impl::lanes(const OutputLayout& outputs) const {
  if (writes_planes(outputs)) return lanes();
  if (context.description().is_gpu()) return 1;
  OutputLayout as_written = outputs;
  if (writes_mesh_as_slots(outputs)) as_written.order = VertexOrder::kSlots;
  if (stages_structs() && detail::fills_vertex_struct(as_written)) return 1;
  if (single_bend && outputs.previous_positions) return 1;
  // The single bend in mesh order: a struct or arrays of their own as vectors (as in
  // slot order, less the padding), every other layout with one lane.
  if (single_bend && outputs.order == VertexOrder::kMesh &&
      !detail::fills_word_struct(as_written) && !detail::fills_own_arrays(as_written)) {
    return 1;
  }
  return lanes();
}

bool ClDeformer::Impl::writes_planes(const OutputLayout& outputs) const {
  return detail::writes_finflex_planes(outputs, shape(1, NormalFormat::kFloat32));
}

// Vertex structs in one buffer and attributes in arrays of their own
// (finflex/internal/cl_outputs.hpp lane_struct_options), transposed into vectors by kernels of
// more than one lane (kernels/cpu/lane_outputs.cl): on CPUs, structs unless staged.
bool ClDeformer::Impl::writes_lane_words(const DeviceBatch& batch) const {
  if (lanes(batch.outputs) == 1) return false;
  if (detail::fills_own_arrays(batch.outputs)) return true;
  return !stages_structs() && detail::fills_word_struct(batch.outputs) &&
         detail::in_one_buffer(batch);
}

bool ClDeformer::Impl::streams_outputs(const DeviceBatch& batch) const {
  // Streaming stores: FinFlex's planes, vertex structs and attribute arrays, stored as
  // vectors.
  const OutputLayout& l = batch.outputs;
  if (lanes(l) == 1 || !(writes_planes(l) || writes_lane_words(batch))) return false;
  // The bytes each vertex slot and instance writes: each attribute's format (a
  // struct's members fill its stride).
  const BatchShape& counts = batch.shape;
  const std::size_t bytes = counts.plane_stride * counts.instance_count * l.bytes_per_vertex();
  return detail::device_streaming_stores(context.description(), tuning.stores, bytes);
}

// ----------------------------------------------------------------------------------
// Checks

void ClDeformer::Impl::check_outputs(const ClJob& job) const {
  const DeviceBatch& batch = *job.outputs;
  const BatchShape& got = batch.shape;
  if (batch.serial == 0) {
    fail_outputs("the batch was not made by a deformer (ClDeformer::allocate, bind or bind_host)");
  }
  if (batch.model_id != model.id()) {
    fail_outputs("the batch was made for another model (make it from this deformer)");
  }
  if (got.vertex_count != model.vertex_count() || got.tangents != tangents_) {
    fail_outputs("the batch is for " + std::to_string(got.vertex_count) + " vertices" +
                 (got.tangents ? " with" : " without") + " tangents; this model has " +
                 std::to_string(model.vertex_count()) + (tangents_ ? " with" : " without") +
                 " tangents (make it from this deformer)");
  }
  if (got.instance_count != job.instances) {
    fail_outputs("the batch holds " + std::to_string(got.instance_count) +
                 " instances, the job deforms " + std::to_string(job.instances));
  }
}

// The layout and its buffers, once per batch: a batch put together by hand must hold
// what its layout says for this model.
void ClDeformer::Impl::check_buffer_sizes(const DeviceBatch& batch) {
  // Checked again when anything the check read has changed since (a batch edited by
  // hand keeps its serial).
  const std::array<cl_mem, 4> buffers = {batch.positions(), batch.normals(), batch.tangents(),
                                         batch.previous_positions()};
  const auto passed = [&](const ValidatedBatch& v) {
    return batch.serial == v.serial && batch.outputs == v.outputs && buffers == v.buffers &&
           batch.shape.instance_count == v.instances;
  };
  if (passed(validated_[0])) return;
  if (passed(validated_[1])) {
    std::swap(validated_[0], validated_[1]);
  } else {
    detail::check_outputs(batch, output_vertices(batch.outputs.order), tangents_, "job.outputs");
    validated_[1] = std::move(validated_[0]);
    validated_[0] = {batch.serial, batch.outputs, buffers, batch.shape.instance_count,
                     batch_state(batch)};
  }
  ++generation_;  // kernels take the batch's arguments again
}

ClDeformer::Impl::BatchState ClDeformer::Impl::batch_state(const DeviceBatch& batch) const {
  BatchState state;
  // Slot s is mesh vertex s (a plain bend): mesh order is slot order without the
  // padding, stored without the vertex_of_slot indirection (and by kernels of more than
  // one lane as vectors, as slot order is).
  const bool mesh_as_slots = writes_mesh_as_slots(batch.outputs);
  DeviceBatch written = batch;
  if (mesh_as_slots) written.outputs.order = VertexOrder::kSlots;
  state.options =
      output_build_options(written.outputs) + staged_struct_options(written, stages_structs()) +
      (writes_lane_words(written) ? lane_struct_options(written) : std::string()) +
      (mesh_as_slots
           ? " -DFF_OUTPUT_LIMIT=" + std::to_string(model.vertex_count()) + "u"
           : detail::plane_stride_option(batch.outputs, shape(1, NormalFormat::kFloat32)));
  // Lanes (and their kind of store) for this batch (lanes(outputs): FinFlex's planes as
  // vectors, other layouts lane by lane or with one lane).
  state.lanes = lanes(batch.outputs);
  state.streams = streams_outputs(batch);
  state.per_item = {per_item(batch.outputs, NormalMode::kRotate),
                    per_item(batch.outputs, NormalMode::kJacobian)};
  return state;
}

void ClDeformer::Impl::check_shape(const ClJob& job) const {
  job.validate(model, job.device.parameters != nullptr);
  if (job.placements != nullptr && job.device.placements != nullptr) {
    throw Error(ErrorCode::kInvalidArgument, "job.placements",
                "job.placements and job.device.placements are both set: give one");
  }
  if (job.list.entries != nullptr) check_list(job);
  check_outputs(job);
}

namespace {

[[noreturn]] void fail_list(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

void check_holds(const cl::Buffer& buffer, std::size_t entries, const std::string& field) {
  const std::size_t size = buffer.getInfo<CL_MEM_SIZE>();
  if (size < entries * sizeof(cl_uint)) {
    fail_list(field, "holds " + std::to_string(size) + " bytes, " + std::to_string(entries) +
                         " cl_uint need " + std::to_string(entries * sizeof(cl_uint)));
  }
}

}  // namespace

// A listed job (ClInstanceList): its inputs on the device, its buffers large enough.
void ClDeformer::Impl::check_list(const ClJob& job) const {
  const ClInstanceList& list = job.list;
  if (job.device.parameters == nullptr) {
    fail_list("job.list", "a listed job reads its values from job.device.parameters (null)");
  }
  if (job.placements != nullptr) {
    fail_list("job.list",
              "a listed job reads its placements from job.device.placements, "
              "not job.placements");
  }
  if (list.counts == nullptr) fail_list("job.list.counts", "null: the list's length is needed");
  if (list.sources == 0 || list.sources > kMaxDeviceInstances) {
    fail_list("job.list.sources", std::to_string(list.sources) +
                                      " is not a number of instances "
                                      "(expected 1 to " +
                                      std::to_string(kMaxDeviceInstances) + ")");
  }
  if (list.first > 0xffffffffu - job.instances) {
    fail_list("job.list.first", std::to_string(list.first) + " is past 2^32 entries");
  }
  check_holds(*list.entries, list.first + job.instances, "job.list.entries");
  if (list.count_index > 0xffffffffu) {
    fail_list("job.list.count_index", std::to_string(list.count_index) + " is past 2^32 entries");
  }
  check_holds(*list.counts, list.count_index + 1, "job.list.counts");
}

void ClDeformer::Impl::check(const ClJob& job) const {
  check_shape(job);
  if (job.device.parameters == nullptr) checker_.check(job.rows(), job.clamp);
}

// ----------------------------------------------------------------------------------
// Kernels

ClDeformer::Impl::BoundKernel& ClDeformer::Impl::kernel(std::size_t index, const ClJob& job) {
  const bool placed = job.placements != nullptr || job.device.placements != nullptr;
  const detail::KernelVariant variant{
      index,  job.normals,           current_batch().options, batch_per_item(job.normals),
      placed, current_batch().lanes, current_batch().streams, job.list.entries != nullptr};
  auto found = kernels_.find(variant);
  if (found == kernels_.end()) {
    const std::size_t fused = fused_launches_.size();
    const std::string name = single_bend     ? "single_bend"
                             : index < fused ? "rig_fused_" + std::to_string(index)
                                             : "rig_pass_" + std::to_string(index - fused);
    found =
        kernels_.emplace(variant, BoundKernel{context.kernel(name, program_, variant.options())})
            .first;
  }
  return found->second;
}

void ClDeformer::Impl::ensure_scratch(std::size_t instances) {
  if (scratch_sets_ == 0 || instances <= scratch_instances_) return;
  const BatchShape scratch_layout = shape(instances, NormalFormat::kFloat32);
  const std::size_t bytes = detail::position_bytes(scratch_layout);
  scratch_.clear();
  for (std::size_t k = 0; k < 3 * scratch_sets_; ++k) {
    const bool tangent = k % 3 == 2;
    scratch_.push_back(
        detail::make_large_buffer(context, tangent && !tangents_ ? sizeof(float) : bytes));
  }
  scratch_instances_ = instances;
  ++generation_;
}

void ClDeformer::Impl::ensure_derived(std::size_t instances) {
  if (derived_per_instance_ == 0 || instances <= derived_instances_) return;
  derived_ = detail::make_buffer(context.context(), CL_MEM_READ_WRITE,
                                 instances * derived_per_instance_ * sizeof(float));
  derived_instances_ = instances;
  ++generation_;
}

// A job's own derived values: kInvalidArgument naming "job.device.derived" when the
// model has none or the buffer is smaller than the frame's.
void ClDeformer::Impl::check_derived_buffer(const cl::Buffer& buffer, std::size_t instances) const {
  const std::string field = "job.device.derived";
  if (derived_per_instance_ == 0) {
    throw Error(ErrorCode::kInvalidArgument, field,
                field + " is set, but the model's rig has no derived values (no spine)");
  }
  const std::size_t needed = instances * derived_per_instance_ * sizeof(float);
  const std::size_t size = buffer.getInfo<CL_MEM_SIZE>();
  if (size < needed) {
    throw Error(ErrorCode::kInvalidArgument, field,
                field + " holds " + std::to_string(size) + " bytes: " + std::to_string(instances) +
                    " instances of " + std::to_string(derived_per_instance_) + " floats need " +
                    std::to_string(needed));
  }
}

// rig_prepare over the job's inputs: the derived values from the frame's values.
void ClDeformer::Impl::prepare_derived(const ClJob& job, const FrameInputs& inputs,
                                       std::vector<cl::Event>* kernel_events) {
  const std::size_t instances = input_instances(job);
  if (instances == 0) return;
  if (!prepare_()) {
    // From a one-lane build of the program the frame's kernels come from (the same
    // build when they have one lane): it works on instances, not on vertex slots.
    const bool placed = job.placements != nullptr || job.device.placements != nullptr;
    const detail::KernelVariant variant{
        0, job.normals, current_batch().options, batch_per_item(job.normals), placed, 1};
    prepare_ = context.kernel("rig_prepare", program_, variant.options());
  }
  cl_uint arg = 0;
  auto set = [&](const auto& value) { check_cl(prepare_.setArg(arg++, value), "clSetKernelArg"); };
  set(*inputs.parameters);
  set(static_cast<cl_uint>(model.values_per_instance()));
  set(derived_);
  set(static_cast<cl_uint>(derived_per_instance_));
  set(static_cast<cl_uint>(instances));
  // device_table_items work-items per instance, in groups of table_group_size
  // (kernels/rig.cl).
  const std::size_t items = tuning.table_items;
  const std::size_t group = detail::table_group_size(items);
  const std::size_t global = (instances * items + group - 1) / group * group;
  cl::Event prepared;
  check_cl(context.queue().enqueueNDRangeKernel(prepare_, cl::NullRange, cl::NDRange(global),
                                                cl::NDRange(group), nullptr,
                                                kernel_events ? &prepared : nullptr),
           "clEnqueueNDRangeKernel rig_prepare");
  if (kernel_events) kernel_events->push_back(prepared);
}

// kernels/single_bend.cl's and kernels/rig.cl's arguments, in their order.
cl_uint ClDeformer::Impl::set_arguments(cl::Kernel& kernel, std::size_t index, const ClJob& job,
                                        const FrameInputs& inputs, cl_uint* list_argument) const {
  const DeviceBatch& batch = *job.outputs;
  cl_uint arg = 0;
  auto set = [&](const auto& value) { check_cl(kernel.setArg(arg++, value), "clSetKernelArg"); };
  set(rest_positions_);
  set(rest_normals_);
  set(rest_tangents_);
  const bool pass = !single_bend && index >= fused_launches_.size();
  if (pass) {
    // Both scratch sets (rest-mesh stand-ins where a set is not needed: never touched).
    for (std::size_t k = 0; k < 6; ++k) {
      const cl::Buffer* rest[3] = {&rest_positions_, &rest_normals_, &rest_tangents_};
      set(k < scratch_.size() ? scratch_[k] : *rest[k % 3]);
    }
  }
  set(*inputs.parameters);
  if (!single_bend) {
    set(static_cast<cl_uint>(model.values_per_instance()));
    set(group_paths_);
    set(*inputs.derived);
    set(static_cast<cl_uint>(derived_per_instance_));
  }
  set(*inputs.placements);
  set(batch.positions);
  set(batch.normals);
  set(batch.tangents);
  set(batch.previous_positions);
  const cl_uint out_layout = arg;
  set(output_layout_argument(batch.outputs, batch.frames_written > 0));
  set(vertex_of_slot_);
  set(static_cast<cl_uint>(slot_count_));
  set(static_cast<cl_uint>(job.instances));
  if (single_bend) {
    for (const cl_float4& value : back_transform_) set(value);
  }
  *list_argument = arg;
  return out_layout;
}

// A listed job's arguments (kernels/common/instance_list.cl), after the others: set
// every frame, since the list may change without the batch changing.
void ClDeformer::Impl::set_list_arguments(cl::Kernel& kernel, cl_uint first_argument,
                                          const ClInstanceList& list) const {
  cl_uint arg = first_argument;
  auto set = [&](const auto& value) { check_cl(kernel.setArg(arg++, value), "clSetKernelArg"); };
  set(*list.entries);
  set(static_cast<cl_uint>(list.first));
  set(*list.counts);
  set(static_cast<cl_uint>(list.count_index));
  set(static_cast<cl_uint>(list.sources));
}

void ClDeformer::Impl::launch(BoundKernel& bound, const ClJob& job, std::size_t first_group,
                              std::size_t end_group, std::vector<cl::Event>* kernel_events,
                              cl::Event* done) {
  // An event only where one is asked for: the frame's last kernel, or every kernel for
  // profiling (creating events costs host time on some drivers).
  cl::Event own;
  cl::Event* event = done ? done : kernel_events ? &own : nullptr;
  const std::size_t per = batch_per_item(job.normals);
  // A work-group covers kWorkGroupSize slots whatever the lanes: the rig kernels tell
  // components apart by work-group (kernels/rig.cl).
  // With lanes, kLaneGroupRows instance rows (the kernels skip those past the
  // last instance).
  const std::size_t items_per_group = kWorkGroupSize / current_batch().lanes;
  const cl::NDRange offset(first_group * items_per_group, 0);
  std::size_t rows = (job.instances + per - 1) / per;
  if (job.list.entries != nullptr) {
    // A list's length is known on the device only: rows enough to fill the device,
    // striding over the list (kernels/common/instance_list.cl).
    // GPUs: 8,192 groups of 64, twice what an H200 holds at once (132 SMs of 32): an
    // empty list costs a launch of 8.7 us there, a full one 4 % more than with 32,768
    // groups, whose empty launch took 23.4 us (docs/levels-of-detail.md "The farm").
    const std::size_t most_groups = context.description().is_gpu() ? 8192 : 4096;
    rows = std::min(rows, std::max<std::size_t>(1, most_groups / (end_group - first_group)));
  }
  const cl::NDRange global((end_group - first_group) * items_per_group,
                           internal::launch_rows(rows, current_batch().lanes));
  check_cl(context.queue().enqueueNDRangeKernel(
               bound.kernel, offset, global,
               cl::NDRange(items_per_group, internal::group_rows(current_batch().lanes)), nullptr,
               event),
           "clEnqueueNDRangeKernel");
  if (kernel_events) kernel_events->push_back(*event);
}

// ----------------------------------------------------------------------------------
// A frame

// The frame's values and placements on the device: uploaded from the job's host
// arrays through the staging rings (checked, or copied when `checked` already), or the
// job's own device buffers. The uploads wait for job.wait.
ClDeformer::Impl::FrameInputs ClDeformer::Impl::upload_inputs(const ClJob& job, bool checked) {
  const std::size_t per_instance = model.values_per_instance();
  const std::size_t instances = job.instances;
  FrameInputs inputs;
  const std::vector<cl::Event>* wait = job.wait;
  if (job.device.parameters) {
    inputs.parameters = job.device.parameters;
  } else {
    const std::size_t values = instances * per_instance;
    float* staged = upload_.acquire(context, values);
    const std::size_t stride = job.parameters.stride ? job.parameters.stride : per_instance;
    if (checked && !job.clamp && stride == per_instance && values > 0) {
      std::memcpy(staged, job.parameters.data, values * sizeof(float));
    } else {
      checker_.check(job.rows(), job.clamp, staged);
    }
    if (upload_.upload(context, wait)) ++generation_;
    wait = nullptr;  // the in-order queue runs the rest after the upload
    inputs.parameters = &upload_.buffer();
  }
  if (job.device.placements) {
    inputs.placements = job.device.placements;
  } else if (job.placements) {
    float* staged = placement_upload_.acquire(context, instances * kPlacementFloats);
    for (std::size_t i = 0; i < instances; ++i) {
      PlacementRecord record;
      try {
        record = placement_record(job.placements[i]);
      } catch (const Error& e) {
        const std::string field = "job.placements[" + std::to_string(i) + "]";
        throw Error(e.code(), field, field + ": " + e.what());
      }
      std::copy(record.begin(), record.end(), staged + i * kPlacementFloats);
    }
    if (placement_upload_.upload(context, wait)) ++generation_;
    wait = nullptr;
    inputs.placements = &placement_upload_.buffer();
  } else {
    inputs.placements = &no_placements_;
  }
  if (wait && !wait->empty()) {
    check_cl(context.queue().enqueueBarrierWithWaitList(wait, nullptr),
             "clEnqueueBarrierWithWaitList");
  }
  return inputs;
}

cl::Event ClDeformer::Impl::enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events,
                                    bool checked) {
  if (!checked) check_shape(job);
  const std::lock_guard<std::mutex> lock(frame_mutex_);
  if (kernel_events) kernel_events->clear();
  check_buffer_sizes(*job.outputs);
  if (job.outputs->host_mapped) detail::unmap_host_outputs(context, *job.outputs);
  const std::size_t instances = job.instances;
  FrameInputs inputs = upload_inputs(job, checked);

  RigPath path = job.path == RigPath::kAuto ? automatic_path : job.path;
  if (pass_count == 0) path = RigPath::kFused;  // no stage at all: the fused copy
  if (path == RigPath::kPasses && !single_bend) ensure_scratch(instances);
  const std::size_t sources = input_instances(job);
  if (job.device.derived != nullptr) {
    // Checked once per buffer and size (the check queries the buffer's size).
    if ((*job.device.derived)() != checked_derived_() || sources > checked_derived_instances_) {
      check_derived_buffer(*job.device.derived, sources);
      checked_derived_ = *job.device.derived;  // held, so its handle stays this buffer's
      checked_derived_instances_ = sources;
    }
    inputs.derived = job.device.derived;
  } else {
    if (derived_per_instance_ > 0) {
      ensure_derived(sources);
      prepare_derived(job, inputs, kernel_events);
    }
    inputs.derived = &derived_;
  }

  auto run = [&](std::size_t index, std::size_t first_group, std::size_t end_group, bool last,
                 cl::Event* done) {
    BoundKernel& bound = kernel(index, job);
    if (bound.batch_serial != job.outputs->serial || bound.generation != generation_ ||
        bound.parameters != (*inputs.parameters)() || bound.placements != (*inputs.placements)() ||
        bound.derived != (*inputs.derived)()) {
      bound.out_layout_argument =
          set_arguments(bound.kernel, index, job, inputs, &bound.list_argument);
      bound.batch_serial = job.outputs->serial;
      bound.generation = generation_;
      bound.parameters = (*inputs.parameters)();
      bound.placements = (*inputs.placements)();
      bound.derived = (*inputs.derived)();
    } else if (job.outputs->outputs.previous_positions) {
      // Whether the positions hold a previous frame changes after the first.
      check_cl(bound.kernel.setArg(
                   bound.out_layout_argument,
                   output_layout_argument(job.outputs->outputs, job.outputs->frames_written > 0)),
               "clSetKernelArg out_layout");
    }
    if (job.list.entries != nullptr)
      set_list_arguments(bound.kernel, bound.list_argument, job.list);
    launch(bound, job, first_group, end_group, kernel_events, last ? done : nullptr);
  };
  cl::Event done;
  if (path == RigPath::kFused || single_bend) {
    // Shared code (RigDispatch::kByPathShape) has a kernel per launch of the plan for
    // one lane, and for more one kernel, rig_fused_0, over every work-group
    // (detail::rig_dispatch_source; the single bend's one launch is that already).
    if (tuning.dispatch == RigDispatch::kByPathShape && current_batch().lanes > 1) {
      run(0, 0, slot_count_ / kWorkGroupSize, true, &done);
    } else {
      for (std::size_t r = 0; r < fused_launches_.size(); ++r) {
        run(r, fused_launches_[r].first, fused_launches_[r].second, r + 1 == fused_launches_.size(),
            &done);
      }
    }
  } else {
    for (std::size_t q = 0; q < pass_count; ++q) {
      run(fused_launches_.size() + q, 0, slot_count_ / kWorkGroupSize, q + 1 == pass_count, &done);
    }
  }
  if (!job.device.parameters) upload_.used(done);
  if (job.placements) placement_upload_.used(done);
  ++job.outputs->frames_written;
  return done;
}

// ----------------------------------------------------------------------------------
// The public class

ClDeformer::ClDeformer(Context& context, const RiggedMesh& model)
    : ClDeformer(context, model, ClTuning{}) {}

ClDeformer::ClDeformer(Context& context, const RiggedMesh& model, const ClTuning& tuning)
    : impl_(std::make_unique<Impl>(context, model, tuning)) {}

ClDeformer::~ClDeformer() = default;

const RiggedMesh& ClDeformer::model() const { return impl_->model; }
Context& ClDeformer::context() const { return impl_->context; }

OutputLayout ClDeformer::layout(std::size_t instances, NormalFormat format) const {
  return detail::planes_outputs(impl_->shape(instances, format));
}

namespace {

// A batch made for `model`: only its jobs may write it.
DeviceBatch made_for(const RiggedMesh& model, DeviceBatch batch) {
  batch.model_id = model.id();
  return batch;
}

}  // namespace

DeviceBatch ClDeformer::allocate(std::size_t instances, NormalFormat format) const {
  return made_for(impl_->model,
                  detail::allocate_batch(impl_->context, impl_->shape(instances, format)));
}

std::size_t ClDeformer::output_vertices(VertexOrder order) const {
  return impl_->output_vertices(order);
}

DeviceBatch ClDeformer::allocate(std::size_t instances, const OutputLayout& outputs) const {
  return made_for(impl_->model, detail::allocate_outputs(impl_->context, impl_->shape(instances),
                                                         outputs, output_vertices(outputs.order)));
}

DeviceBatch ClDeformer::bind(std::size_t instances, const OutputLayout& outputs,
                             const OutputBuffers& buffers) const {
  return made_for(impl_->model,
                  detail::bind_outputs(impl_->context, impl_->shape(instances), outputs, buffers,
                                       output_vertices(outputs.order)));
}

DeviceBatch ClDeformer::bind_host(std::size_t instances, const OutputLayout& outputs,
                                  const HostOutputs& host) const {
  return made_for(impl_->model,
                  detail::bind_host_outputs(impl_->context, impl_->shape(instances), outputs, host,
                                            output_vertices(outputs.order)));
}

void ClDeformer::map_host(DeviceBatch& batch) { detail::map_host_outputs(impl_->context, batch); }
void ClDeformer::unmap_host(DeviceBatch& batch) {
  detail::unmap_host_outputs(impl_->context, batch);
}

cl::Event ClDeformer::enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events) {
  return impl_->enqueue(job, kernel_events, false);
}

void ClDeformer::check(const ClJob& job) const { impl_->check(job); }

DeformedBatch<float> ClDeformer::read(const DeviceBatch& batch) {
  const VertexOrder order = batch.outputs.order;
  DeformedBatch<float> out =
      detail::read_outputs(impl_->context, batch, impl_->output_vertices(order));
  if (order == VertexOrder::kSlots) out.slot_of_vertex = impl_->slot_of_vertex;
  return out;
}

const std::vector<std::uint32_t>& ClDeformer::slot_of_vertex() const {
  return impl_->slot_of_vertex;
}
const std::vector<std::uint32_t>& ClDeformer::remapped_indices() const {
  return impl_->remapped_indices;
}
bool ClDeformer::uses_single_bend_kernel() const { return impl_->single_bend; }
std::size_t ClDeformer::derived_floats_per_instance() const {
  return impl_->derived_per_instance();
}
RigPath ClDeformer::automatic_path() const { return impl_->automatic_path; }

// ----------------------------------------------------------------------------------
// What a deformer chose (finflex/internal/cl_tuning.hpp)

namespace internal {

struct DeformerAccess {
  static const ClDeformer::Impl& impl(const ClDeformer& deformer) { return *deformer.impl_; }
};

std::size_t pass_count(const ClDeformer& deformer) {
  return DeformerAccess::impl(deformer).pass_count;
}
double scratch_records_per_slot(const ClDeformer& deformer) {
  return DeformerAccess::impl(deformer).scratch_records_per_slot;
}
std::size_t instances_per_item(const ClDeformer& deformer, const OutputLayout& outputs,
                               NormalMode normals) {
  return DeformerAccess::impl(deformer).per_item(outputs, normals);
}
std::size_t lanes(const ClDeformer& deformer, const OutputLayout& outputs) {
  return DeformerAccess::impl(deformer).lanes(outputs);
}
bool streams_outputs(const ClDeformer& deformer, const DeviceBatch& batch) {
  return DeformerAccess::impl(deformer).streams_outputs(batch);
}

}  // namespace internal
}  // namespace finflex

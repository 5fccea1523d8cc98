#include <string>

#include "device_batch.hpp"
#include "finflex/error.hpp"
#include "finflex/rig_deformer.hpp"
#include "param_bounds.hpp"
#include "rig_program.hpp"

namespace finflex {
namespace {

constexpr std::size_t kGroupSize = ClDeformer::kLocalSize;

void set_args(cl::Kernel& kernel, cl_uint first, std::initializer_list<const cl::Buffer*> buffers,
              const char* what) {
  cl_uint arg = first;
  for (const cl::Buffer* buffer : buffers) check_cl(kernel.setArg(arg++, *buffer), what);
}

}  // namespace

std::size_t rig_instances_per_work_item(const DeviceDescription& device) {
  return device.type == "GPU" ? 4 : 1;
}

ClRigDeformer::ClRigDeformer(Context& context, const Mesh& mesh, const Rig& rig,
                             std::size_t instances_per_item, RigDispatch dispatch)
    : context_(context),
      rig_(rig),
      limits_(rig_param_limits(rig)),
      bounds_tile_(detail::rig_bounds_tile(limits_)) {
  instances_per_item_ =
      instances_per_item ? instances_per_item : rig_instances_per_work_item(context.description());
  if (dispatch == RigDispatch::kAuto) {
    dispatch = context.description().type == "GPU" ? RigDispatch::kPerComponent
                                                   : RigDispatch::kByPathShape;
  }
  const bool share_code = dispatch == RigDispatch::kByPathShape;
  validate_mesh(mesh);
  vertex_count_ = mesh.vertex_count();
  tangents_ = mesh.has_tangents();
  const detail::SlotLayout slots = detail::make_slot_layout(rig_, vertex_count_, kGroupSize);
  slot_count_ = slots.slot_count;
  slot_of_vertex_ = slots.slot_of_vertex;
  remapped_indices_.reserve(mesh.indices.size());
  for (std::uint32_t index : mesh.indices) remapped_indices_.push_back(slot_of_vertex_[index]);

  const cl::Context& cl_context = context_.context();
  const detail::RestPlanes rest = detail::make_rest_planes(rig_, mesh, slots);
  const std::size_t plane_bytes = rest.positions.size() * sizeof(float);
  rest_positions_ =
      detail::make_buffer(cl_context, CL_MEM_READ_ONLY, plane_bytes, rest.positions.data());
  rest_normals_ =
      detail::make_buffer(cl_context, CL_MEM_READ_ONLY, plane_bytes, rest.normals.data());
  rest_tangents_ = tangents_ ? detail::make_buffer(cl_context, CL_MEM_READ_ONLY, plane_bytes,
                                                   rest.tangents.data())
                             : detail::make_buffer(cl_context, CL_MEM_READ_ONLY, sizeof(float));
  const std::vector<float> frames = detail::stage_frames(rig_);
  stages_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY, frames.size() * sizeof(float),
                                frames.data());
  const std::vector<std::uint32_t> paths = detail::group_path_table(rig_, slots, kGroupSize);
  group_paths_ = detail::make_buffer(cl_context, CL_MEM_READ_ONLY,
                                     paths.size() * sizeof(std::uint32_t), paths.data());

  const detail::PassPlan plan = detail::make_pass_plan(rig_, slots, kGroupSize, share_code);
  const std::vector<detail::FusedLaunch> fused =
      detail::make_fused_plan(rig_, slots, kGroupSize, share_code);
  for (const detail::FusedLaunch& launch : fused)
    fused_launches_.emplace_back(launch.first_group, launch.end_group);
  pass_count_ = plan.passes.size();
  scratch_sets_ = plan.scratch_sets;
  scratch_records_per_slot_ = plan.scratch_records_per_slot;
  automatic_path_ =
      detail::longest_path(rig_) <= kMaxFusedStages ? RigPath::kFused : RigPath::kPasses;
  program_ = {{"bend.cl", "planes.cl", "rig.cl"},
              detail::rig_dispatch_source(rig_, slots, fused, plan, kGroupSize, share_code)};
}

void ClRigDeformer::check(const RigParameters& parameters, bool clamp) const {
  detail::check_rig_params(rig_, limits_, bounds_tile_, parameters, clamp);
}

BatchLayout ClRigDeformer::layout(std::size_t instances, NormalFormat format) const {
  BatchLayout layout;
  layout.normal_format = format;
  layout.vertex_count = vertex_count_;
  layout.instance_count = instances;
  layout.plane_stride = slot_count_;
  layout.tangents = tangents_;
  return layout;
}

DeviceBatch ClRigDeformer::allocate(std::size_t instances, NormalFormat format) const {
  return detail::allocate_batch(context_, layout(instances, format), rig_.params.size());
}

void ClRigDeformer::ensure_scratch(DeviceBatch& batch, std::size_t sets) const {
  const std::size_t bytes = batch.layout.attribute_elements() * sizeof(float);
  const cl::Context& cl_context = context_.context();
  while (batch.scratch.size() < 3 * sets) {
    const bool tangent = batch.scratch.size() % 3 == 2;
    batch.scratch.push_back(detail::make_buffer(cl_context, CL_MEM_READ_WRITE,
                                                tangent && !tangents_ ? sizeof(float) : bytes));
  }
}

// The arguments every rig kernel ends with, from `first` on (kernels/rig.cl): params,
// param_count, stages, group_paths, out_positions, out_normals, out_tangents, stride,
// instances.
void ClRigDeformer::set_batch_args(cl::Kernel& kernel, cl_uint first,
                                   const DeviceBatch& batch) const {
  set_args(kernel, first, {&batch.parameters}, "clSetKernelArg params");
  check_cl(kernel.setArg(first + 1, static_cast<cl_uint>(rig_.params.size())),
           "clSetKernelArg param_count");
  check_cl(kernel.setArg(first + 2, stages_), "clSetKernelArg stages");
  check_cl(kernel.setArg(first + 3, group_paths_), "clSetKernelArg group_paths");
  set_args(kernel, first + 4, {&batch.positions, &batch.normals, &batch.tangents},
           "clSetKernelArg out");
  check_cl(kernel.setArg(first + 7, static_cast<cl_uint>(slot_count_)), "clSetKernelArg stride");
  check_cl(kernel.setArg(first + 8, static_cast<cl_uint>(batch.layout.instance_count)),
           "clSetKernelArg instances");
}

BoundKernel& ClRigDeformer::kernel(std::size_t index, NormalMode normals, NormalFormat format) {
  const auto key = std::make_tuple(index, normals, format);
  auto found = kernels_.find(key);
  if (found == kernels_.end()) {
    const std::size_t fused = fused_launches_.size();
    const std::string name = index < fused ? "rig_fused_" + std::to_string(index)
                                           : "rig_pass_" + std::to_string(index - fused);
    const std::string options =
        std::string("-DFF_NORMALS_JACOBIAN=") + (normals == NormalMode::kJacobian ? "1" : "0") +
        " -DFF_TANGENTS=" + (tangents_ ? "1" : "0") +
        " -DFF_HALF_NORMALS=" + (format == NormalFormat::kHalf ? "1" : "0") +
        " -DFF_INSTANCES_PER_ITEM=" + std::to_string(instances_per_item_);
    found = kernels_.emplace(key, BoundKernel{context_.kernel(name, program_, options)}).first;
  }
  return found->second;
}

cl::Event ClRigDeformer::enqueue(const RigParameters& parameters, NormalMode normals,
                                 DeviceBatch& batch, RigPath path, bool clamp,
                                 const std::vector<cl::Event>* wait,
                                 std::vector<cl::Event>* kernel_events) {
  if (kernel_events) kernel_events->clear();
  if (parameters.instance_count() != batch.layout.instance_count ||
      batch.layout.plane_stride != slot_count_) {
    throw Error(ErrorCode::kInvalidArgument, "parameters",
                "the parameters are for " + std::to_string(parameters.instance_count()) +
                    " instances, the batch holds " + std::to_string(batch.layout.instance_count) +
                    " of this rig");
  }
  std::vector<float>& staged = detail::next_staging(batch);
  detail::check_rig_params_into(rig_, limits_, bounds_tile_, parameters, clamp, staged);
  detail::upload_parameters(context_, batch, staged, wait);
  if (path == RigPath::kAuto) path = automatic_path();

  cl::Event done;
  const cl::Buffer* rest[3] = {&rest_positions_, &rest_normals_, &rest_tangents_};
  if (path == RigPath::kFused || pass_count_ == 0) {
    for (std::size_t r = 0; r < fused_launches_.size(); ++r) {
      const auto [first_group, end_group] = fused_launches_[r];
      const bool last = r + 1 == fused_launches_.size();
      launch(kernel(r, normals, batch.layout.normal_format), batch, {rest[0], rest[1], rest[2]},
             first_group, end_group, kernel_events, last ? &done : nullptr);
    }
    detail::staging_used(batch, done);
    return done;
  }

  // Every pass gets the rest mesh, both scratch sets and the outputs; its generated
  // steps read and write only the ones make_pass_plan chose (unused sets are bound to
  // the rest mesh and never touched).
  ensure_scratch(batch, scratch_sets_);
  const cl::Buffer* sets[2][3] = {{rest[0], rest[1], rest[2]}, {rest[0], rest[1], rest[2]}};
  for (std::size_t k = 0; k < batch.scratch.size() && k < 6; ++k)
    sets[k / 3][k % 3] = &batch.scratch[k];
  for (std::size_t q = 0; q < pass_count_; ++q) {
    launch(kernel(fused_launches_.size() + q, normals, batch.layout.normal_format), batch,
           {rest[0], rest[1], rest[2], sets[0][0], sets[0][1], sets[0][2], sets[1][0], sets[1][1],
            sets[1][2]},
           0, slot_count_ / kGroupSize, kernel_events, q + 1 == pass_count_ ? &done : nullptr);
  }
  detail::staging_used(batch, done);
  return done;
}

void ClRigDeformer::launch(BoundKernel& bound, const DeviceBatch& batch,
                           std::initializer_list<const cl::Buffer*> leading,
                           std::size_t first_group, std::size_t end_group,
                           std::vector<cl::Event>* kernel_events, cl::Event* done) {
  if (!bound.bound_to(batch)) {
    set_args(bound.kernel, 0, leading, "clSetKernelArg rig kernel");
    set_batch_args(bound.kernel, static_cast<cl_uint>(leading.size()), batch);
    bound.mark_bound(batch);
  }
  // An event only where one is asked for: the frame's last kernel, or every kernel for
  // profiling (creating events costs host time on some drivers).
  cl::Event own;
  cl::Event* event = done ? done : kernel_events ? &own : nullptr;
  const cl::NDRange offset(first_group * kGroupSize, 0);
  const cl::NDRange global(
      (end_group - first_group) * kGroupSize,
      (batch.layout.instance_count + instances_per_item_ - 1) / instances_per_item_);
  check_cl(context_.queue().enqueueNDRangeKernel(bound.kernel, offset, global,
                                                 cl::NDRange(kGroupSize, 1), nullptr, event),
           "clEnqueueNDRangeKernel rig kernel");
  if (kernel_events) kernel_events->push_back(*event);
}

DeformedBatch<float> ClRigDeformer::read(const DeviceBatch& batch) {
  DeformedBatch<float> out = detail::read_batch(context_, batch);
  out.slot_of_vertex = slot_of_vertex_;
  return out;
}

}  // namespace finflex

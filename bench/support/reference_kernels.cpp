#include "reference_kernels.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "bench_kernel_sources.hpp"
#include "deformer_report.hpp"
#include "finflex/internal/cl_outputs.hpp"

namespace finflex::bench {
namespace {

ProgramSource bandwidth_program() {
  const std::vector<KernelSource>& sources = bench_kernel_sources();
  const auto found = std::find_if(sources.begin(), sources.end(), [](const KernelSource& k) {
    return k.file_name == "bandwidth.cl";
  });
  return {common_kernel_files(), "", found->text};
}

// The deformation kernels' NDRange (deformer_report.hpp).
cl::Event launch(Context& context, cl::Kernel& kernel, std::size_t vertices, std::size_t instances,
                 std::size_t per_item, std::size_t lanes) {
  cl::Event done;
  check_cl(
      context.queue().enqueueNDRangeKernel(
          kernel, cl::NullRange, deformation_global_range(vertices, instances, per_item, lanes),
          deformation_local_range(lanes), nullptr, &done),
      "clEnqueueNDRangeKernel");
  return done;
}

}  // namespace

cl::Event enqueue_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                             std::size_t instances_per_item, WriteValues values, std::size_t lanes,
                             bool streaming) {
  if (values == WriteValues::kDeviceDefault) {
    values = context.description().is_gpu() ? WriteValues::kVarying : WriteValues::kConstant;
  }
  // Mesh order is written as the slot order of its vertices without the padding
  // (FF_OUTPUT_LIMIT): the same bytes at the same places, by the fastest stores of that
  // layout (vectors, a staged struct), whatever the model's slots.
  const bool cpu_lanes = lanes > 1 && !context.description().is_gpu();
  DeviceBatch as_written = batch;
  const bool mesh_as_slots = batch.outputs.order == VertexOrder::kMesh;
  if (mesh_as_slots) as_written.outputs.order = VertexOrder::kSlots;
  const std::string options =
      std::string("-DFF_INSTANCES_PER_ITEM=") + std::to_string(instances_per_item) +
      (values == WriteValues::kVarying ? " -DFF_VARYING_WRITES=1" : "") +
      output_build_options(as_written.outputs) +
      staged_struct_options(as_written, context.description().is_gpu()) +
      (cpu_lanes ? lane_struct_options(as_written) : std::string()) +
      (mesh_as_slots ? " -DFF_OUTPUT_LIMIT=" + std::to_string(vertices) + "u" : std::string()) +
      (lanes > 1 ? " -DFF_LANES=" + std::to_string(lanes) +
                       " -DFF_STREAMING_STORES=" + (streaming ? "1" : "0")
                 : std::string());
  cl::Kernel kernel = context.kernel("write_outputs", bandwidth_program(), options);
  cl_uint arg = 0;
  auto set = [&](const auto& value) { check_cl(kernel.setArg(arg++, value), "clSetKernelArg"); };
  set(batch.positions);
  set(batch.normals);
  set(batch.tangents);
  set(batch.previous_positions);
  set(output_layout_argument(batch.outputs, true));
  set(batch.positions);  // vertex_of_slot: unread (write_outputs indexes by v)
  set(static_cast<cl_uint>(vertices));
  set(static_cast<cl_uint>(batch.shape.instance_count));
  set(1.0f);
  return launch(context, kernel, vertices, batch.shape.instance_count, instances_per_item, lanes);
}

cl::Event enqueue_copy_rest(Context& context, const cl::Buffer& source, DeviceBatch& batch) {
  cl::Kernel kernel = context.kernel("copy_rest", bandwidth_program(), "");
  cl_uint arg = 0;
  auto set = [&](const auto& value) { check_cl(kernel.setArg(arg++, value), "clSetKernelArg"); };
  set(source);
  set(batch.positions);
  set(batch.normals);
  set(static_cast<cl_uint>(batch.shape.plane_stride));
  return launch(context, kernel, batch.shape.plane_stride, batch.shape.instance_count, 1, 1);
}

}  // namespace finflex::bench

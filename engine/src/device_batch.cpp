#include "device_batch.hpp"

#include <algorithm>
#include <string>

#include "finflex/error.hpp"

namespace finflex::detail {

cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, std::size_t bytes,
                       const void* host) {
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(context, flags | (host ? CL_MEM_COPY_HOST_PTR : 0), bytes,
                    const_cast<void*>(host), &status);
  check_cl(status, "clCreateBuffer");
  return buffer;
}

DeviceBatch allocate_batch(Context& context, const BatchLayout& layout,
                           std::size_t parameters_per_instance) {
  if (layout.instance_count == 0) {
    throw Error(ErrorCode::kInvalidArgument, "instances", "instances = 0: at least one is needed");
  }
  const std::size_t bytes = layout.attribute_elements() * sizeof(float);
  const DeviceDescription& device = context.description();
  if (bytes > device.max_allocation_bytes) {
    throw Error(ErrorCode::kOutOfRange, "instances",
                "instances = " + std::to_string(layout.instance_count) + " needs " +
                    std::to_string(bytes) + " bytes per attribute, above the device's largest " +
                    "allocation (" + std::to_string(device.max_allocation_bytes) + " bytes on '" +
                    device.device_name + "')");
  }
  const cl::Context& cl_context = context.context();
  DeviceBatch batch;
  batch.layout = layout;
  batch.positions = make_buffer(cl_context, CL_MEM_READ_WRITE, bytes);
  batch.normals = make_buffer(cl_context, CL_MEM_READ_WRITE, bytes);
  batch.tangents =
      make_buffer(cl_context, CL_MEM_READ_WRITE, layout.tangents ? bytes : sizeof(float));
  const std::size_t values =
      std::max<std::size_t>(layout.instance_count * parameters_per_instance, 1);
  batch.parameters = make_buffer(cl_context, CL_MEM_READ_ONLY, values * sizeof(float));
  batch.staged_parameters.reserve(values);
  return batch;
}

void wait_for_previous_upload(DeviceBatch& batch) {
  if (batch.parameters_uploaded()) check_cl(batch.parameters_uploaded.wait(), "clWaitForEvents");
}

void upload_parameters(Context& context, DeviceBatch& batch, const std::vector<cl::Event>* wait) {
  if (batch.staged_parameters.empty()) return;
  check_cl(context.queue().enqueueWriteBuffer(
               batch.parameters, CL_FALSE, 0, batch.staged_parameters.size() * sizeof(float),
               batch.staged_parameters.data(), wait, &batch.parameters_uploaded),
           "clEnqueueWriteBuffer parameters");
}

DeformedBatch<float> read_batch(Context& context, const DeviceBatch& batch) {
  DeformedBatch<float> out;
  out.resize(batch.layout);
  cl::CommandQueue& queue = context.queue();
  const std::size_t bytes = batch.layout.attribute_elements() * sizeof(float);
  check_cl(queue.enqueueReadBuffer(batch.positions, CL_TRUE, 0, bytes, out.positions.data()),
           "clEnqueueReadBuffer positions");
  check_cl(queue.enqueueReadBuffer(batch.normals, CL_TRUE, 0, bytes, out.normals.data()),
           "clEnqueueReadBuffer normals");
  if (batch.layout.tangents) {
    check_cl(queue.enqueueReadBuffer(batch.tangents, CL_TRUE, 0, bytes, out.tangents.data()),
             "clEnqueueReadBuffer tangents");
  }
  return out;
}

}  // namespace finflex::detail

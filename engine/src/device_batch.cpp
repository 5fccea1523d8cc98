#include "device_batch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
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
  const std::size_t direction_bytes = layout.attribute_elements() * layout.normal_component_bytes();
  static std::atomic<std::uint64_t> next_serial{1};
  DeviceBatch batch;
  batch.serial = next_serial++;
  batch.layout = layout;
  batch.positions = make_buffer(cl_context, CL_MEM_READ_WRITE, bytes);
  batch.normals = make_buffer(cl_context, CL_MEM_READ_WRITE, direction_bytes);
  batch.tangents =
      make_buffer(cl_context, CL_MEM_READ_WRITE, layout.tangents ? direction_bytes : sizeof(float));
  const std::size_t values =
      std::max<std::size_t>(layout.instance_count * parameters_per_instance, 1);
  batch.parameters = make_buffer(cl_context, CL_MEM_READ_ONLY, values * sizeof(float));
  for (std::vector<float>& slot : batch.staging) slot.reserve(values);
  return batch;
}

std::vector<float>& next_staging(DeviceBatch& batch) {
  cl::Event& used = batch.staging_done[batch.next_staging];
  if (used()) check_cl(used.wait(), "clWaitForEvents");
  return batch.staging[batch.next_staging];
}

void upload_parameters(Context& context, DeviceBatch& batch, const std::vector<float>& staged,
                       const std::vector<cl::Event>* wait) {
  if (staged.empty()) return;
  check_cl(context.queue().enqueueWriteBuffer(batch.parameters, CL_FALSE, 0,
                                              staged.size() * sizeof(float), staged.data(), wait,
                                              nullptr),
           "clEnqueueWriteBuffer parameters");
}

void staging_used(DeviceBatch& batch, const cl::Event& frame_done) {
  batch.staging_done[batch.next_staging] = frame_done;
  batch.next_staging = (batch.next_staging + 1) % DeviceBatch::kStagingSlots;
}

namespace {

// IEEE 754 binary16 to float (normals and tangents are finite and in [-1, 1], but
// every class is handled).
float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const std::uint32_t exponent = (h >> 10) & 0x1fu;
  const std::uint32_t mantissa = h & 0x3ffu;
  float magnitude;
  if (exponent == 0) {
    magnitude = std::ldexp(static_cast<float>(mantissa), -24);  // subnormal or zero
  } else if (exponent == 31) {
    magnitude =
        mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  } else {
    magnitude = std::ldexp(static_cast<float>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
  }
  return sign ? -magnitude : magnitude;
}

// Reads a normal or tangent array in the layout's format into floats.
void read_directions(cl::CommandQueue& queue, const cl::Buffer& buffer, const BatchLayout& layout,
                     std::vector<float>& out) {
  const std::size_t count = layout.attribute_elements();
  if (layout.normal_format == NormalFormat::kFloat32) {
    check_cl(queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data()),
             "clEnqueueReadBuffer");
    return;
  }
  std::vector<std::uint16_t> halves(count);
  check_cl(
      queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(std::uint16_t), halves.data()),
      "clEnqueueReadBuffer");
  for (std::size_t k = 0; k < count; ++k) out[k] = half_to_float(halves[k]);
}

}  // namespace

DeformedBatch<float> read_batch(Context& context, const DeviceBatch& batch) {
  DeformedBatch<float> out;
  out.resize(batch.layout);
  cl::CommandQueue& queue = context.queue();
  const std::size_t bytes = batch.layout.attribute_elements() * sizeof(float);
  check_cl(queue.enqueueReadBuffer(batch.positions, CL_TRUE, 0, bytes, out.positions.data()),
           "clEnqueueReadBuffer positions");
  read_directions(queue, batch.normals, batch.layout, out.normals);
  if (batch.layout.tangents) read_directions(queue, batch.tangents, batch.layout, out.tangents);
  return out;
}

}  // namespace finflex::detail

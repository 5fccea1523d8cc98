#include "device_buffers.hpp"

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

std::size_t position_bytes(const BatchLayout& layout) {
  return layout.attribute_elements() * sizeof(float);
}

std::size_t direction_bytes(const BatchLayout& layout) {
  return layout.attribute_elements() * layout.normal_component_bytes();
}

DeviceBatch allocate_batch(Context& context, const BatchLayout& layout) {
  if (layout.instance_count == 0) {
    throw Error(ErrorCode::kInvalidArgument, "instances", "instances = 0: at least one is needed");
  }
  if (layout.instance_count > kMaxDeviceInstances) {
    throw Error(ErrorCode::kOutOfRange, "instances",
                "instances = " + std::to_string(layout.instance_count) + " is above the limit " +
                    std::to_string(kMaxDeviceInstances) +
                    " of one batch (the kernels count instances in 32 bits)");
  }
  const DeviceDescription& device = context.description();
  const std::size_t instance_bytes = 3 * layout.plane_stride * sizeof(float);
  if (layout.instance_count > device.max_allocation_bytes / instance_bytes) {
    throw Error(ErrorCode::kOutOfRange, "instances",
                "instances = " + std::to_string(layout.instance_count) + " needs " +
                    std::to_string(instance_bytes) + " bytes each per attribute, above the " +
                    "device's largest allocation (" +
                    std::to_string(device.max_allocation_bytes) + " bytes on '" +
                    device.device_name + "')");
  }
  const std::size_t bytes = position_bytes(layout);
  const cl::Context& cl_context = context.context();
  static std::atomic<std::uint64_t> next_serial{1};
  DeviceBatch batch;
  batch.serial = next_serial++;
  batch.layout = layout;
  batch.positions = make_buffer(cl_context, CL_MEM_READ_WRITE, bytes);
  batch.normals = make_buffer(cl_context, CL_MEM_READ_WRITE, direction_bytes(layout));
  batch.tangents = make_buffer(cl_context, CL_MEM_READ_WRITE,
                               layout.tangents ? direction_bytes(layout) : sizeof(float));
  return batch;
}

std::vector<float>& ParameterUpload::acquire(std::size_t values) {
  cl::Event& last = done_[next_];
  if (last()) check_cl(last.wait(), "clWaitForEvents");
  staging_[next_].resize(values);
  return staging_[next_];
}

bool ParameterUpload::upload(Context& context, const std::vector<cl::Event>* wait) {
  const std::vector<float>& staged = staging_[next_];
  bool replaced = false;
  if (staged.size() > device_values_ || !device_()) {
    // A new buffer for a larger frame; kernels still queued keep the old one alive.
    device_values_ = std::max<std::size_t>(staged.size(), 1);
    device_ = make_buffer(context.context(), CL_MEM_READ_ONLY, device_values_ * sizeof(float));
    replaced = true;
  }
  if (!staged.empty()) {
    check_cl(context.queue().enqueueWriteBuffer(device_, CL_FALSE, 0,
                                                staged.size() * sizeof(float), staged.data(),
                                                wait, nullptr),
             "clEnqueueWriteBuffer parameters");
  } else if (wait && !wait->empty()) {
    check_cl(context.queue().enqueueBarrierWithWaitList(wait, nullptr),
             "clEnqueueBarrierWithWaitList");
  }
  return replaced;
}

void ParameterUpload::used(const cl::Event& frame_done) {
  done_[next_] = frame_done;
  next_ = (next_ + 1) % kSlots;
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
  check_cl(queue.enqueueReadBuffer(batch.positions, CL_TRUE, 0, position_bytes(batch.layout),
                                   out.positions.data()),
           "clEnqueueReadBuffer positions");
  read_directions(queue, batch.normals, batch.layout, out.normals);
  if (batch.layout.tangents) read_directions(queue, batch.tangents, batch.layout, out.tangents);
  return out;
}

}  // namespace finflex::detail

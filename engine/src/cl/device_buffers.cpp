#include "cl/device_buffers.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "cl/output_buffers.hpp"
#include "cl/output_options.hpp"
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

std::size_t position_bytes(const BatchShape& layout) {
  return layout.attribute_elements() * sizeof(float);
}

std::size_t direction_bytes(const BatchShape& layout) {
  return layout.attribute_elements() * layout.normal_component_bytes();
}

DeviceBatch allocate_batch(Context& context, const BatchShape& layout) {
  return allocate_outputs(context, layout, planes_outputs(layout), layout.plane_stride);
}

cl::Buffer make_buffer_over(const cl::Context& context, void* host, std::size_t bytes) {
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(context, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes, host, &status);
  check_cl(status, "clCreateBuffer (CL_MEM_USE_HOST_PTR)");
  return buffer;
}

ParameterUpload::~ParameterUpload() {
  for (Staging& staging : staging_) release(staging);
}

void ParameterUpload::release(Staging& staging) {
  if (staging.mapped) {
    // Unmapped on the frames' queue, in order after every upload from it, without
    // waiting (a frame may still wait behind a closed FrameGate); the queued unmap
    // holds the buffer until it runs. Nothing may throw from a destructor: a failed
    // unmap leaves the driver to reclaim the buffer with its context.
    staging.queue.enqueueUnmapMemObject(staging.pinned, staging.mapped);
    staging.queue.flush();
  }
  staging = Staging{};
}

float* ParameterUpload::acquire(Context& context, std::size_t values) {
  Staging& staging = staging_[next_];
  const bool finished = staging.finished && staging.finished->load(std::memory_order_acquire);
  if (staging.done() && !finished) check_cl(staging.done.wait(), "clWaitForEvents");
  if (values > staging.capacity) {
    // Grown by half again, so frames of slowly growing sizes do not map every time.
    const std::size_t capacity = std::max(values, staging.capacity + staging.capacity / 2);
    release(staging);
    staging.queue = context.queue();
    staging.pinned = make_buffer(context.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR,
                                 capacity * sizeof(float));
    cl_int status = CL_SUCCESS;
    staging.mapped = static_cast<float*>(
        context.map_queue().enqueueMapBuffer(staging.pinned, CL_TRUE, CL_MAP_WRITE, 0,
                                             capacity * sizeof(float), nullptr, nullptr, &status));
    check_cl(status, "clEnqueueMapBuffer (staging)");
    staging.capacity = capacity;
  }
  staging.size = values;
  return values ? staging.mapped : nullptr;
}

bool ParameterUpload::upload(Context& context, const std::vector<cl::Event>* wait) {
  const Staging& staged = staging_[next_];
  bool replaced = false;
  if (staged.size > device_values_ || !device_()) {
    // A new buffer for a larger frame; kernels still queued keep the old one alive.
    device_values_ = std::max<std::size_t>(staged.size, 1);
    device_ = make_buffer(context.context(), CL_MEM_READ_ONLY, device_values_ * sizeof(float));
    replaced = true;
  }
  if (staged.size > 0) {
    check_cl(context.queue().enqueueWriteBuffer(device_, CL_FALSE, 0, staged.size * sizeof(float),
                                                staged.mapped, wait, nullptr),
             "clEnqueueWriteBuffer parameters");
  } else if (wait && !wait->empty()) {
    check_cl(context.queue().enqueueBarrierWithWaitList(wait, nullptr),
             "clEnqueueBarrierWithWaitList");
  }
  return replaced;
}

namespace {

// The completion callback of a staging area's frame: sets the area's flag and lets go of
// its share of it. An abnormal end (a negative status) leaves the flag clear, so that
// acquire()'s wait reports it.
void CL_CALLBACK mark_finished(cl_event, cl_int status, void* flag) {
  auto* shared = static_cast<std::shared_ptr<std::atomic<bool>>*>(flag);
  if (status == CL_COMPLETE) (*shared)->store(true, std::memory_order_release);
  delete shared;
}

}  // namespace

void ParameterUpload::used(const cl::Event& frame_done) {
  Staging& staging = staging_[next_];
  staging.done = frame_done;
  staging.finished = std::make_shared<std::atomic<bool>>(false);
  auto* callback_share = new std::shared_ptr<std::atomic<bool>>(staging.finished);
  if (staging.done.setCallback(CL_COMPLETE, mark_finished, callback_share) != CL_SUCCESS) {
    delete callback_share;
    staging.finished.reset();
  }
  next_ = (next_ + 1) % kSlots;
}

}  // namespace finflex::detail

// Device buffers of the OpenCL backend: allocation within the device's limits, the
// default outputs of a batch, and the per-frame parameter upload.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"

namespace finflex::detail {

// A buffer of `bytes` (copied from `host` when given); kOpenCL on failure.
cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, std::size_t bytes,
                       const void* host = nullptr);

// The outputs of `layout` in FinFlex's planes, one buffer per attribute.
// kInvalidArgument for no instances, kOutOfRange naming "instances" above the device's
// largest allocation.
DeviceBatch allocate_batch(Context& context, const BatchShape& layout);

// A buffer over the caller's host memory (CL_MEM_USE_HOST_PTR).
cl::Buffer make_buffer_over(const cl::Context& context, void* host, std::size_t bytes);

// Bytes the outputs of `layout` need per attribute: positions, and normals and
// tangents (in the layout's normal format).
std::size_t position_bytes(const BatchShape& layout);
std::size_t direction_bytes(const BatchShape& layout);

// The per-frame upload of a deformer's (or a driver's) inputs, for frames in flight:
// a ring of staging areas in pinned host memory (a mapped CL_MEM_ALLOC_HOST_PTR
// buffer: the device copies from it by DMA, so an upload costs the host no copy of its
// own), each reused only once the frame that last used it is done (the last kernel of
// that frame, after its upload in the in-order queue, proves it), and one device
// buffer that grows to the largest frame.
class ParameterUpload {
 public:
  static constexpr std::size_t kSlots = 3;

  ParameterUpload() = default;
  ParameterUpload(const ParameterUpload&) = delete;
  ParameterUpload& operator=(const ParameterUpload&) = delete;
  ~ParameterUpload();

  // The next staging area, `values` floats, once its last frame is done (long done, in
  // a steady frame loop); null for 0 values.
  float* acquire(Context& context, std::size_t values);
  // Uploads the area acquire() gave without blocking, after `wait`. Returns true
  // when the device buffer was replaced (kernels must be given the new one).
  bool upload(Context& context, const std::vector<cl::Event>* wait);
  // Records the frame's last kernel event for the staging area it used (with a
  // completion callback), and moves on.
  void used(const cl::Event& frame_done);

  const cl::Buffer& buffer() const { return device_; }

 private:
  struct Staging {
    cl::CommandQueue queue;  // the frames' queue, which uploads from it and unmaps it
    cl::Buffer pinned;
    float* mapped = nullptr;
    std::size_t capacity = 0;  // floats
    std::size_t size = 0;      // floats of this frame
    cl::Event done;
    // Set by the runtime's callback once `done` completed, so a frame's acquire() makes
    // no driver call for an area long done (a wait on a complete event cost 7-12 us of a
    // frame on NVIDIA's OpenCL); shared with the callback, which may run after this
    // upload is gone. Null when the callback could not be set: then acquire() waits.
    std::shared_ptr<std::atomic<bool>> finished;
  };
  static void release(Staging& staging);

  std::array<Staging, kSlots> staging_;  // mapped on Context::map_queue()
  std::size_t next_ = 0;
  cl::Buffer device_;
  std::size_t device_values_ = 0;
};

}  // namespace finflex::detail

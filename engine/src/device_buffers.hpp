// Device buffers of the OpenCL backend: allocation within the device's limits, the
// outputs of a batch, the per-frame parameter upload, and the blocking read-back.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"

namespace finflex::detail {

// A buffer of `bytes` (copied from `host` when given); kOpenCL on failure.
cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, std::size_t bytes,
                       const void* host = nullptr);

// The outputs of `layout`, one buffer per attribute. kInvalidArgument for no
// instances, kOutOfRange naming "instances" above the device's largest allocation.
DeviceBatch allocate_batch(Context& context, const BatchLayout& layout);

// Bytes the outputs of `layout` need per attribute: positions, and normals and
// tangents (in the layout's normal format).
std::size_t position_bytes(const BatchLayout& layout);
std::size_t direction_bytes(const BatchLayout& layout);

// The parameter upload of a deformer, for frames in flight: a ring of host staging
// buffers, each reused only once the frame that last used it is done (the last
// kernel of that frame, after its upload in the in-order queue, proves it), and one
// device buffer that grows to the largest frame.
class ParameterUpload {
 public:
  static constexpr std::size_t kSlots = 3;

  // The next staging buffer, resized to `values` floats, once its last frame is done
  // (long done, in a steady frame loop).
  std::vector<float>& acquire(std::size_t values);
  // Uploads the buffer acquire() gave without blocking, after `wait`. Returns true
  // when the device buffer was replaced (kernels must be given the new one).
  bool upload(Context& context, const std::vector<cl::Event>* wait);
  // Records the frame's last kernel event for the staging buffer it used, and moves on.
  void used(const cl::Event& frame_done);

  const cl::Buffer& buffer() const { return device_; }

 private:
  std::array<std::vector<float>, kSlots> staging_;
  std::array<cl::Event, kSlots> done_;
  std::size_t next_ = 0;
  cl::Buffer device_;
  std::size_t device_values_ = 0;
};

// Blocking read of a batch's outputs (slot order).
DeformedBatch<float> read_batch(Context& context, const DeviceBatch& batch);

}  // namespace finflex::detail

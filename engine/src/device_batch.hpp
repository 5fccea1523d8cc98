// Device buffers of a batch, shared by the OpenCL deformers: allocation within the
// device's limits, the per-frame parameter upload, and the blocking read-back.
#pragma once

#include <cstddef>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/cl_context.hpp"
#include "finflex/cl_deformer.hpp"

namespace finflex::detail {

// A buffer of `bytes` (copied from `host` when given); kOpenCL on failure.
cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, std::size_t bytes,
                       const void* host = nullptr);

// Outputs of `layout` (one buffer per attribute) and a parameter buffer of
// `parameters_per_instance` floats per instance. Throws kInvalidArgument for no
// instances, kOutOfRange naming "instances" above the device's largest allocation.
DeviceBatch allocate_batch(Context& context, const BatchLayout& layout,
                           std::size_t parameters_per_instance);

// The batch's next staging slot for a frame's parameters, once the frame that last
// used it is done (long done, in a steady frame loop).
std::vector<float>& next_staging(DeviceBatch& batch);

// Uploads `staged` (the slot next_staging() gave) without blocking, after `wait`.
void upload_parameters(Context& context, DeviceBatch& batch, const std::vector<float>& staged,
                       const std::vector<cl::Event>* wait);

// Records the frame's last kernel event for the slot its parameters used, and moves
// the ring on.
void staging_used(DeviceBatch& batch, const cl::Event& frame_done);

// Blocking read of the outputs.
DeformedBatch<float> read_batch(Context& context, const DeviceBatch& batch);

}  // namespace finflex::detail

// The benchmarks' reference kernels (bench/kernels/bandwidth.cl): a write-only kernel
// over a batch's outputs, in the NDRange shape of the deformation kernels, so that a
// benchmark measures the device's write bandwidth next to them in the same run; and a
// copy of rest-sized planes into every instance.
#pragma once

#include <cstddef>

#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::bench {

// What the write-only kernel writes: one value everywhere (no arithmetic at all), or
// values that differ per vertex and instance (a few integer operations; GPUs may
// compress uniform data on its way to memory and write it faster than any real output
// could go).
enum class WriteValues {
  kDeviceDefault,  // kVarying on GPUs, kConstant on CPUs
  kConstant,
  kVarying,
};

// Writes every output the batch's layout has (positions, normals, tangents, previous
// positions, in their formats and arrangements) for `vertices` vertices
// (ClDeformer::output_vertices of its order), `instances_per_item` instances and
// `lanes` slots per work-item (the deformer's: kernel_shape, deformer_report.hpp;
// more than one lane: FinFlex's float32 planes only, with streaming
// stores or ordinary ones: ClTuning::stores; for another layout the kernel's build
// fails, kernels/cpu/lane_outputs.cl). Returns the kernel's event.
cl::Event enqueue_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                             std::size_t instances_per_item,
                             WriteValues values = WriteValues::kDeviceDefault,
                             std::size_t lanes = 1, bool streaming = true);

// Copies 6 planes of `source` (positions and normals of plane_stride slots) into every
// instance of the batch's float32 outputs. Returns the kernel's event.
cl::Event enqueue_copy_rest(Context& context, const cl::Buffer& source, DeviceBatch& batch);

}  // namespace finflex::bench

// A batch's outputs on the device (finflex/device_batch.hpp, finflex/output_layout.hpp):
// making batches (allocated, the caller's buffers, the caller's host memory), checking
// them against a deformer's vertex count, mapping host batches, and reading any layout
// back as float planes.
#pragma once

#include <cstddef>
#include <string>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/output_layout.hpp"

namespace finflex::detail {

// FinFlex's planes for `layout` (its plane stride, normal format and tangents).
OutputLayout planes_outputs(const BatchLayout& layout);

// True when `outputs` writes what planes_outputs(counts) writes with normals in float32
// or half, where it does: float32 planes for positions, normals (and tangents when
// `counts` has them) in float32 or half planes, at FinFlex's offsets and strides, in
// slot order, previous positions (if any) in float32 planes laid out as the positions.
// The outputs kernels of more than one lane store as vectors
// (kernels/cpu/lane_outputs.cl).
bool writes_finflex_planes(const OutputLayout& outputs, const BatchLayout& counts);
// " -DFF_PLANE_STRIDE=<stride>u" when `outputs` are FinFlex's planes of `counts`
// (kernels/common/outputs.cl compiles their places in), else "".
std::string plane_stride_option(const OutputLayout& outputs, const BatchLayout& counts);

// Whether positions, normals (and tangents) are float32x3 members that fill one vertex
// struct (the same vertex and instance strides, 12 bytes a member), in slot order and
// without previous positions: what staged_struct_options stages, given one buffer.
bool fills_vertex_struct(const OutputLayout& outputs);
// The same for kernels of more than one lane (lane_struct_options): members float32x3
// or x4, float16x4, snorm16x4 or octahedral16x2, each on a 4-byte word, that fill the
// struct.
bool fills_word_struct(const OutputLayout& outputs);
// Whether the batch's positions, normals (and tangents) share one buffer.
bool in_one_buffer(const DeviceBatch& batch);
// Whether every attribute is its own tightly packed array (vertex stride its format's
// bytes) in one of fills_word_struct's formats, each on a 4-byte word, in slot order and
// without previous positions: what lane_struct_options also takes (FF_LANE_ARRAYS).
bool fills_own_arrays(const OutputLayout& outputs);

// Checks that `batch` holds `counts.instance_count` instances of `vertices` vertices
// (slots or mesh vertices, as its order says) in its layout, in buffers large enough,
// tangents only for a mesh that has them. kInvalidArgument naming `field` (e.g.
// "job.outputs") and the rule broken.
void check_outputs(const DeviceBatch& batch, std::size_t vertices, bool mesh_tangents,
                   const std::string& field);

// A batch of `counts` in `outputs`: buffers allocated (one per attribute, sized by the
// layout), the caller's buffers, or buffers over the caller's host memory. Checked as
// check_outputs does, naming "outputs".
DeviceBatch allocate_outputs(Context& context, const BatchLayout& counts,
                             const OutputLayout& outputs, std::size_t vertices);
DeviceBatch bind_outputs(Context& context, const BatchLayout& counts, const OutputLayout& outputs,
                         const OutputBuffers& buffers, std::size_t vertices);
DeviceBatch bind_host_outputs(Context& context, const BatchLayout& counts,
                              const OutputLayout& outputs, const HostOutputs& host,
                              std::size_t vertices);

// Host batches: map their buffers for reading on the host (blocking: the caller's
// memory holds the frame when it returns), and unmap them before the next frame.
void map_host_outputs(Context& context, DeviceBatch& batch);
void unmap_host_outputs(Context& context, DeviceBatch& batch);

// Blocking read of every attribute of `batch` into float planes of `vertices` a plane
// (the batch's vertex order; the caller sets slot_of_vertex for slot order).
DeformedBatch<float> read_outputs(Context& context, const DeviceBatch& batch, std::size_t vertices);

}  // namespace finflex::detail

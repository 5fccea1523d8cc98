// How a batch's outputs shape the kernels that write them: FinFlex's own planes, the
// layouts whose places the kernels compile in, and the vertex structs and arrays that
// kernels of more than one lane store as vectors. The build options themselves are
// finflex/internal/cl_outputs.hpp's.
#pragma once

#include <string>

#include "finflex/batch.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/output_layout.hpp"

namespace finflex::detail {

// FinFlex's planes for `layout` (its plane stride, normal format and tangents).
OutputLayout planes_outputs(const BatchShape& layout);

// True when `outputs` writes what planes_outputs(counts) writes with normals in float32
// or half, where it does: float32 planes for positions, normals (and tangents when
// `counts` has them) in float32 or half planes, at FinFlex's offsets and strides, in
// slot order, previous positions (if any) in float32 planes laid out as the positions.
// The outputs kernels of more than one lane store as vectors
// (kernels/cpu/lane_outputs.cl).
bool writes_finflex_planes(const OutputLayout& outputs, const BatchShape& counts);
// " -DFF_PLANE_STRIDE=<stride>u" when `outputs` are FinFlex's planes of `counts`
// (kernels/common/outputs.cl compiles their places in), else "".
std::string plane_stride_option(const OutputLayout& outputs, const BatchShape& counts);

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

}  // namespace finflex::detail

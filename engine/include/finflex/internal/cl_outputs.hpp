// How the kernels are told an OutputLayout (finflex/output_layout.hpp), for kernels of
// one's own that write outputs as FinFlex's do (kernels/common/outputs.cl's
// store_outputs): the build options that fix each attribute's format and arrangement,
// and the numbers (offsets and strides, in scalars of each format) of the `out_layout`
// kernel argument.
#pragma once

#include <string>

#include <CL/opencl.hpp>

#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/export.hpp"
#include "finflex/output_layout.hpp"

namespace finflex {

// -D options of kernels/common/outputs.cl for `layout` (FF_POSITION_FORMAT, ...,
// FF_TANGENTS, FF_PREVIOUS, FF_MESH_ORDER).
FINFLEX_API std::string output_build_options(const OutputLayout& layout);

// For a batch whose positions, normals (and tangents) are float32x3 attributes of one
// vertex struct that they fill (one buffer, one vertex stride of 24 or 36 bytes, slot
// order, no previous positions): the options (FF_STAGED_STRUCT, ...) with which the
// kernels put a work-group's structs together in local memory and write them as one
// contiguous run. Empty for any other layout, or when `staged` is false. Append to
// output_build_options(batch.outputs). FinFlex stages on GPUs (ClTuning::struct_stores).
FINFLEX_API std::string staged_struct_options(const DeviceBatch& batch, bool staged);

// A vertex struct for kernels of more than one lane (CPUs, ClTuning::lanes): its
// attributes in one buffer, slot order, no previous positions, filling the struct,
// each starting on a 4-byte word, in float32x3 or x4, float16x4, snorm16x4 or
// octahedral16x2 (FF_LANE_STRUCT); or each attribute in a tightly packed array of its
// own (vertex stride its format's bytes; the same formats, slot order, no previous
// positions; FF_LANE_ARRAYS). Each work-item's structs (an array's: one attribute's)
// are transposed from its lanes' vectors in registers and stored as whole vectors
// (kernels/cpu/lane_outputs.cl). Empty for any other layout.
// Append to output_build_options(batch.outputs) where FF_LANES > 1 and the structs are
// not staged; one-lane builds ignore it.
FINFLEX_API std::string lane_struct_options(const DeviceBatch& batch);

// The `out_layout` argument; `previous_valid`: the positions' place holds the previous
// frame (DeviceBatch::frames_written > 0).
FINFLEX_API cl_ulong16 output_layout_argument(const OutputLayout& layout, bool previous_valid);

}  // namespace finflex

// How the kernels are told an OutputLayout (finflex/output_layout.hpp), for kernels of
// one's own that write outputs as FinFlex's do (kernels/common/outputs.cl's
// store_outputs): the build options that fix each attribute's format and arrangement,
// and the numbers (offsets and strides, in scalars of each format) of the `out_layout`
// kernel argument.
#pragma once

#include <string>

#include <CL/opencl.hpp>

#include "finflex/export.hpp"
#include "finflex/output_layout.hpp"

namespace finflex {

// -D options of kernels/common/outputs.cl for `layout` (FF_POSITION_FORMAT, ...,
// FF_TANGENTS, FF_PREVIOUS, FF_MESH_ORDER).
FINFLEX_API std::string output_build_options(const OutputLayout& layout);

// The `out_layout` argument; `previous_valid`: the positions' place holds the previous
// frame (DeviceBatch::frames_written > 0).
FINFLEX_API cl_ulong16 output_layout_argument(const OutputLayout& layout, bool previous_valid);

}  // namespace finflex

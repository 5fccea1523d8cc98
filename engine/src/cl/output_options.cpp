#include "cl/output_options.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>

#include "finflex/internal/cl_outputs.hpp"

namespace finflex::detail {
namespace {

// Whether positions, normals (and tangents) are packed members that fill one vertex
// struct (the same vertex and instance strides, their bytes adding up to the stride,
// each on a 4-byte word), in slot order and without previous positions, each in a
// format `takes` accepts.
template <typename Takes>
bool fills_struct(const OutputLayout& l, Takes takes) {
  if (l.order != VertexOrder::kSlots || l.previous_positions) return false;
  // No allocation: ClDeformer asks this every frame (its work-item shape).
  const auto all = l.written();
  const std::size_t count = l.tangents ? 3 : 2;
  const std::size_t stride = l.positions.vertex_stride;
  std::size_t start = l.positions.offset, bytes = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const AttributeLayout* a = all[k];
    if (a->arrangement != Arrangement::kPacked || !takes(a->format) || a->vertex_stride != stride ||
        a->instance_stride != l.positions.instance_stride || a->offset % 4 != 0) {
      return false;
    }
    start = std::min(start, a->offset);
    bytes += format_bytes(a->format);
  }
  if (bytes != stride || l.positions.instance_stride % 4 != 0) return false;
  // validate_output_layout keeps the members apart, so at these offsets they tile it.
  for (std::size_t k = 0; k < count; ++k) {
    if (all[k]->offset - start >= stride) return false;
  }
  return true;
}

// The formats whose components kernels of more than one lane pack into 4-byte words.
bool word_format(AttributeFormat f) {
  return f == AttributeFormat::kFloat32x3 || f == AttributeFormat::kFloat32x4 ||
         f == AttributeFormat::kFloat16x4 || f == AttributeFormat::kSnorm16x4 ||
         f == AttributeFormat::kOctahedral16x2;
}

// `outputs` are FinFlex's planes of `counts`, normals (and tangents) in `format`.
bool writes_planes_in(const OutputLayout& outputs, const BatchShape& counts, NormalFormat format) {
  BatchShape in_format = counts;
  in_format.normal_format = format;
  const OutputLayout planes = planes_outputs(in_format);
  return outputs.order == VertexOrder::kSlots &&
         (!outputs.previous_positions || *outputs.previous_positions == planes.positions) &&
         outputs.positions == planes.positions && outputs.normals == planes.normals &&
         outputs.tangents == planes.tangents;
}

}  // namespace

OutputLayout planes_outputs(const BatchShape& layout) {
  const AttributeFormat directions = layout.normal_format == NormalFormat::kHalf
                                         ? AttributeFormat::kFloat16x3
                                         : AttributeFormat::kFloat32x3;
  OutputLayout outputs;
  outputs.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, layout.plane_stride);
  outputs.normals = AttributeLayout::planes(directions, layout.plane_stride);
  if (layout.tangents) outputs.tangents = AttributeLayout::planes(directions, layout.plane_stride);
  return outputs;
}

bool writes_finflex_planes(const OutputLayout& outputs, const BatchShape& counts) {
  return writes_planes_in(outputs, counts, NormalFormat::kFloat32) ||
         writes_planes_in(outputs, counts, NormalFormat::kHalf);
}

std::string plane_stride_option(const OutputLayout& outputs, const BatchShape& counts) {
  return writes_finflex_planes(outputs, counts)
             ? " -DFF_PLANE_STRIDE=" + std::to_string(counts.plane_stride) + "u"
             : "";
}

bool fills_vertex_struct(const OutputLayout& l) {
  return fills_struct(l, [](AttributeFormat f) { return f == AttributeFormat::kFloat32x3; });
}

bool fills_word_struct(const OutputLayout& l) { return fills_struct(l, word_format); }

bool in_one_buffer(const DeviceBatch& batch) {
  return batch.normals() == batch.positions() &&
         (!batch.outputs.tangents || batch.tangents() == batch.positions());
}

bool fills_own_arrays(const OutputLayout& l) {
  if (l.order != VertexOrder::kSlots || l.previous_positions) return false;
  // No allocation: ClDeformer asks this every frame (its work-item shape).
  const auto all = l.written();
  const std::size_t count = l.tangents ? 3 : 2;
  for (std::size_t k = 0; k < count; ++k) {
    const AttributeLayout* a = all[k];
    if (a->arrangement != Arrangement::kPacked || !word_format(a->format) ||
        a->vertex_stride != format_bytes(a->format) || a->offset % 4 != 0 ||
        a->instance_stride % 4 != 0) {
      return false;
    }
  }
  return true;
}

}  // namespace finflex::detail

namespace finflex {
namespace {

// kernels/common/outputs.cl's format numbers: finflex::AttributeFormat's order.
int format_number(AttributeFormat format) { return static_cast<int>(format); }

// `flag`=1 and the struct's numbers (kernels/common/outputs.cl FF_STAGED_STRUCT: words
// of 4 bytes) for a vertex struct in one buffer that `fills` says the kernels take;
// empty for any other layout.
std::string vertex_struct_options(const DeviceBatch& batch, bool fills, const char* flag) {
  const OutputLayout& l = batch.outputs;
  if (!fills || !detail::in_one_buffer(batch)) return "";
  std::size_t start = std::min(l.positions.offset, l.normals.offset);
  if (l.tangents) start = std::min(start, l.tangents->offset);
  auto floats_in = [&](const AttributeLayout& a) { return std::to_string((a.offset - start) / 4); };
  return std::string(" -D") + flag +
         "=1 -DFF_STAGED_FLOATS=" + std::to_string(l.positions.vertex_stride / 4) +
         " -DFF_STAGED_POSITION=" + floats_in(l.positions) +
         " -DFF_STAGED_NORMAL=" + floats_in(l.normals) +
         " -DFF_STAGED_TANGENT=" + (l.tangents ? floats_in(*l.tangents) : std::string("0"));
}

// An attribute's layout, or the default one when it is not written (the kernels do not
// touch it then; its numbers only keep the build options and arguments complete).
const AttributeLayout& or_default(const std::optional<AttributeLayout>& a) {
  static const AttributeLayout unused;
  return a ? *a : unused;
}

}  // namespace

std::string output_build_options(const OutputLayout& layout) {
  auto attribute = [](const char* name, const AttributeLayout& a) {
    return std::string(" -DFF_") + name + "_FORMAT=" + std::to_string(format_number(a.format)) +
           " -DFF_" + name + "_PACKED=" + (a.arrangement == Arrangement::kPacked ? "1" : "0");
  };
  return attribute("POSITION", layout.positions) + attribute("NORMAL", layout.normals) +
         attribute("TANGENT", or_default(layout.tangents)) +
         attribute("PREVIOUS", or_default(layout.previous_positions)) +
         " -DFF_TANGENTS=" + (layout.tangents ? "1" : "0") +
         " -DFF_PREVIOUS=" + (layout.previous_positions ? "1" : "0") +
         " -DFF_MESH_ORDER=" + (layout.order == VertexOrder::kMesh ? "1" : "0");
}

std::string staged_struct_options(const DeviceBatch& batch, bool staged) {
  if (!staged) return "";
  return vertex_struct_options(batch, detail::fills_vertex_struct(batch.outputs),
                               "FF_STAGED_STRUCT");
}

std::string lane_struct_options(const DeviceBatch& batch) {
  if (detail::fills_own_arrays(batch.outputs)) return " -DFF_LANE_ARRAYS=1";
  return vertex_struct_options(batch, detail::fills_word_struct(batch.outputs), "FF_LANE_STRUCT");
}

cl_ulong16 output_layout_argument(const OutputLayout& layout, bool previous_valid) {
  cl_ulong16 out{};
  auto put = [&](int first, const AttributeLayout& a) {
    const std::size_t scalar = scalar_bytes(a.format);
    const std::size_t step =
        a.arrangement == Arrangement::kPacked ? a.vertex_stride / scalar : a.plane_stride;
    out.s[first] = a.offset / scalar;
    out.s[first + 1] = step;
    out.s[first + 2] = a.instance_stride / scalar;
  };
  put(0, layout.positions);
  put(3, layout.normals);
  put(6, or_default(layout.tangents));
  put(9, or_default(layout.previous_positions));
  out.s[12] = previous_valid ? 1 : 0;
  return out;
}

}  // namespace finflex

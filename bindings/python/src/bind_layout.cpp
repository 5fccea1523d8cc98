// Output layouts (finflex/output_layout.hpp): where and how a batch's attributes are
// written, as descriptors a renderer's vertex buffers are made from. Formats, orders and
// arrangements are the C++ names as strings ("float32x3", "mesh", "packed").
#include <cstddef>
#include <optional>
#include <string>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "bindings.hpp"

namespace finflex::python {
namespace {

std::string describe(const AttributeLayout& a) {
  std::string text = std::string("finflex.AttributeLayout(") + to_string(a.format) + ", " +
                     to_string(a.arrangement) + ", offset=" + std::to_string(a.offset);
  if (a.arrangement == Arrangement::kPacked) {
    text += ", vertex_stride=" + std::to_string(a.vertex_stride);
  } else {
    text += ", plane_stride=" + std::to_string(a.plane_stride);
  }
  return text + ", instance_stride=" + std::to_string(a.instance_stride) + ")";
}

}  // namespace

void bind_layout(nb::module_& m) {
  nb::class_<AttributeLayout>(
      m, "AttributeLayout",
      "Where one attribute of a batch is written, in bytes from its buffer's start: packed, "
      "offset + i * instance_stride + v * vertex_stride (the components adjacent); planes, "
      "offset + i * instance_stride + (c * plane_stride + v) * component_bytes.")
      .def(nb::init<>())
      .def_prop_rw(
          "format", [](const AttributeLayout& a) { return std::string(to_string(a.format)); },
          [](AttributeLayout& a, const std::string& f) { a.format = parse_attribute_format(f); },
          "'float32x3', 'float32x4', 'float16x3', 'float16x4', 'snorm16x4' or "
          "'octahedral16x2'.")
      .def_prop_rw(
          "arrangement",
          [](const AttributeLayout& a) { return std::string(to_string(a.arrangement)); },
          [](AttributeLayout& a, const std::string& t) { a.arrangement = parse_arrangement(t); },
          "'planes' (structure of arrays) or 'packed' (an element's components together).")
      .def_rw("offset", &AttributeLayout::offset, "Bytes from the buffer's start.")
      .def_rw("vertex_stride", &AttributeLayout::vertex_stride,
              "Packed: bytes from a vertex to the next.")
      .def_rw("plane_stride", &AttributeLayout::plane_stride,
              "Planes: elements in a plane (at least the vertices).")
      .def_rw("instance_stride", &AttributeLayout::instance_stride,
              "Bytes from an instance to the next.")
      .def_static(
          "planes",
          [](const std::string& format, std::size_t plane_stride, std::size_t offset) {
            return AttributeLayout::planes(parse_attribute_format(format), plane_stride, offset);
          },
          nb::arg("format"), nb::arg("plane_stride"), nb::arg("offset") = 0,
          "FinFlex's planes: one instance's three planes after the other's.")
      .def_static(
          "packed",
          [](const std::string& format, std::size_t vertices, std::size_t vertex_stride,
             std::size_t offset, std::size_t instance_stride) {
            return AttributeLayout::packed(parse_attribute_format(format), vertices, vertex_stride,
                                           offset, instance_stride);
          },
          nb::arg("format"), nb::arg("vertices"), nb::arg("vertex_stride") = 0,
          nb::arg("offset") = 0, nb::arg("instance_stride") = 0,
          "Packed elements; vertex_stride 0: tightly packed, instance_stride 0: an "
          "instance's vertices right after the other's.")
      .def("__eq__", [](const AttributeLayout& a, const AttributeLayout& b) { return a == b; })
      .def("__repr__", &describe);

  nb::class_<OutputLayout>(
      m, "OutputLayout",
      "Where and how a batch's outputs are written (Deformer.layout gives FinFlex's planes "
      "to start from; Deformer.allocate takes any layout it checks).")
      .def(nb::init<>())
      .def_prop_rw(
          "order", [](const OutputLayout& l) { return std::string(to_string(l.order)); },
          [](OutputLayout& l, const std::string& t) { l.order = parse_vertex_order(t); },
          "'slots' (the deformer's vertex slots: draw with Deformer.remapped_indices) or "
          "'mesh' (the mesh's own vertex order and indices).")
      .def_rw("positions", &OutputLayout::positions, "'float32x3' or 'float32x4'.")
      .def_rw("normals", &OutputLayout::normals)
      .def_rw("tangents", &OutputLayout::tangents,
              "None: not written; the mesh must have tangents otherwise.")
      .def_rw("previous_positions", &OutputLayout::previous_positions,
              "None: not written; else each frame's positions before it (motion vectors).")
      .def_static("required_bytes", &OutputLayout::required_bytes, nb::arg("attribute"),
                  nb::arg("instances"), nb::arg("vertices"),
                  "Bytes a buffer needs to hold `attribute` for `instances` instances of "
                  "`vertices` vertices.")
      .def("__eq__", [](const OutputLayout& a, const OutputLayout& b) { return a == b; })
      .def("__repr__", [](const OutputLayout& l) {
        auto optional = [](const std::optional<AttributeLayout>& a) {
          return a ? describe(*a) : std::string("None");
        };
        return std::string("finflex.OutputLayout(order=") + to_string(l.order) +
               ", positions=" + describe(l.positions) + ", normals=" + describe(l.normals) +
               ", tangents=" + optional(l.tangents) +
               ", previous_positions=" + optional(l.previous_positions) + ")";
      });
}

}  // namespace finflex::python

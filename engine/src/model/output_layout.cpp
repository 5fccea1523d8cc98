#include "finflex/output_layout.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "finflex/error.hpp"

namespace finflex {
namespace {

struct FormatInfo {
  AttributeFormat format;
  const char* name;
  std::size_t bytes;
  std::size_t scalar;
};

constexpr FormatInfo kFormats[] = {
    {AttributeFormat::kFloat32x3, "float32x3", 12, 4},
    {AttributeFormat::kFloat32x4, "float32x4", 16, 4},
    {AttributeFormat::kFloat16x3, "float16x3", 6, 2},
    {AttributeFormat::kFloat16x4, "float16x4", 8, 2},
    {AttributeFormat::kSnorm16x4, "snorm16x4", 8, 2},
    {AttributeFormat::kOctahedral16x2, "octahedral16x2", 4, 4},
};

const FormatInfo& info(AttributeFormat format) {
  for (const FormatInfo& entry : kFormats) {
    if (entry.format == format) return entry;
  }
  throw Error(ErrorCode::kInvalidArgument, "format", "format: unknown attribute format");
}

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

std::string bytes(std::size_t n) { return std::to_string(n) + " bytes"; }

// a * b + c, or kInvalidArgument naming `field` when it does not fit a size_t.
std::size_t checked(std::size_t a, std::size_t b, std::size_t c, const std::string& field) {
  constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();
  if (b != 0 && a > (kMax - c) / b) fail(field, "the layout's extent overflows 64 bits");
  return a * b + c;
}

// The byte range [first, end) an attribute's elements lie in.
struct Footprint {
  std::size_t first = 0;
  std::size_t end = 0;
};

Footprint footprint(const AttributeLayout& a, std::size_t instances, std::size_t vertices) {
  return {a.offset, OutputLayout::required_bytes(a, instances, vertices)};
}

void check_attribute(const AttributeLayout& a, const std::string& field, bool position,
                     std::size_t instances, std::size_t vertices) {
  const FormatInfo& f = info(a.format);
  const std::string format = std::string("a ") + f.name + " element";
  if (position && a.format != AttributeFormat::kFloat32x3 &&
      a.format != AttributeFormat::kFloat32x4) {
    fail(field + ".format",
         std::string(f.name) + " is not a position format (float32x3 or float32x4)");
  }
  const std::size_t scalar = f.scalar;
  auto multiple = [&](std::size_t value, const char* name) {
    if (value % scalar != 0) {
      fail(field + "." + name, bytes(value) + " is not a multiple of " + std::to_string(scalar) +
                                   " (" + format + "'s alignment)");
    }
  };
  multiple(a.offset, "offset");
  multiple(a.instance_stride, "instance_stride");
  if (a.arrangement == Arrangement::kPlanes) {
    if (a.format != AttributeFormat::kFloat32x3 && a.format != AttributeFormat::kFloat16x3) {
      fail(field + ".format",
           std::string(f.name) + " cannot be planes (planes hold float32x3 or float16x3)");
    }
    if (a.plane_stride < vertices) {
      fail(field + ".plane_stride", std::to_string(a.plane_stride) + " elements is less than the " +
                                        std::to_string(vertices) + " vertices");
    }
    const std::size_t instance_bytes = checked(3 * scalar, a.plane_stride, 0, field);
    if (instances > 1 && a.instance_stride < instance_bytes) {
      fail(field + ".instance_stride", bytes(a.instance_stride) + " is less than an instance's " +
                                           "three planes (" + bytes(instance_bytes) + ")");
    }
    return;
  }
  multiple(a.vertex_stride, "vertex_stride");
  const std::size_t element = f.bytes;
  // Instances one after the other, or side by side within each vertex.
  const bool vertices_apart = vertices <= 1 || a.vertex_stride >= element;
  const std::size_t instance_span = checked(vertices - 1, a.vertex_stride, element, field);
  const bool instances_after = instances <= 1 || a.instance_stride >= instance_span;
  const std::size_t vertex_span = checked(instances - 1, a.instance_stride, element, field);
  const bool instances_beside = (instances <= 1 || a.instance_stride >= element) &&
                                (vertices <= 1 || a.vertex_stride >= vertex_span);
  if (!vertices_apart && !instances_beside) {
    fail(field + ".vertex_stride",
         bytes(a.vertex_stride) + " is less than " + format + " (" + bytes(element) + ")");
  }
  if (!(vertices_apart && instances_after) && !instances_beside) {
    fail(field + ".instance_stride",
         bytes(a.instance_stride) + " overlaps the previous instance: an instance of " +
             std::to_string(vertices) + " vertices spans " + bytes(instance_span));
  }
}

// Two attributes of one buffer: apart, or interleaved in one vertex struct.
void check_shared(const AttributeLayout& a, const std::string& a_name, const AttributeLayout& b,
                  const std::string& b_name, std::size_t instances, std::size_t vertices) {
  const Footprint fa = footprint(a, instances, vertices);
  const Footprint fb = footprint(b, instances, vertices);
  if (fa.end <= fb.first || fb.end <= fa.first) return;  // separate ranges
  const bool interleavable =
      a.arrangement == Arrangement::kPacked && b.arrangement == Arrangement::kPacked &&
      a.vertex_stride == b.vertex_stride && a.instance_stride == b.instance_stride &&
      a.vertex_stride > 0 && (instances <= 1 || a.instance_stride % a.vertex_stride == 0);
  if (interleavable) {
    // On the lattice of vertex_stride: [0, E_a) and [d, d + E_b) apart on its circle.
    const std::size_t stride = a.vertex_stride;
    const bool a_first = a.offset <= b.offset;
    const AttributeLayout& low = a_first ? a : b;
    const AttributeLayout& high = a_first ? b : a;
    const std::size_t d = (high.offset - low.offset) % stride;
    if (format_bytes(low.format) <= d && d + format_bytes(high.format) <= stride) return;
  }
  fail(b_name, "shares bytes with " + a_name + " in one buffer (" + a_name + " at [" +
                   std::to_string(fa.first) + ", " + std::to_string(fa.end) + "), " + b_name +
                   " at [" + std::to_string(fb.first) + ", " + std::to_string(fb.end) +
                   "); interleaved attributes need equal strides and disjoint offsets within one "
                   "vertex_stride)");
}

}  // namespace

const char* to_string(AttributeFormat format) { return info(format).name; }

AttributeFormat parse_attribute_format(const std::string& text, const std::string& field) {
  std::string names;
  for (const FormatInfo& entry : kFormats) {
    if (text == entry.name) return entry.format;
    names += std::string(names.empty() ? "" : ", ") + entry.name;
  }
  fail(field, "'" + text + "' is not a format (" + names + ")");
}

std::size_t format_bytes(AttributeFormat format) { return info(format).bytes; }
std::size_t scalar_bytes(AttributeFormat format) { return info(format).scalar; }

const char* to_string(VertexOrder order) { return order == VertexOrder::kMesh ? "mesh" : "slots"; }

VertexOrder parse_vertex_order(const std::string& text, const std::string& field) {
  if (text == "slots") return VertexOrder::kSlots;
  if (text == "mesh") return VertexOrder::kMesh;
  fail(field, "'" + text + "' is not a vertex order (slots, mesh)");
}

const char* to_string(Arrangement arrangement) {
  return arrangement == Arrangement::kPacked ? "packed" : "planes";
}

Arrangement parse_arrangement(const std::string& text, const std::string& field) {
  if (text == "planes") return Arrangement::kPlanes;
  if (text == "packed") return Arrangement::kPacked;
  fail(field, "'" + text + "' is not an arrangement (planes, packed)");
}

AttributeLayout AttributeLayout::planes(AttributeFormat format, std::size_t plane_stride,
                                        std::size_t offset) {
  AttributeLayout layout;
  layout.format = format;
  layout.arrangement = Arrangement::kPlanes;
  layout.offset = offset;
  layout.plane_stride = plane_stride;
  layout.instance_stride = 3 * plane_stride * scalar_bytes(format);
  return layout;
}

AttributeLayout AttributeLayout::packed(AttributeFormat format, std::size_t vertices,
                                        std::size_t vertex_stride, std::size_t offset,
                                        std::size_t instance_stride) {
  AttributeLayout layout;
  layout.format = format;
  layout.arrangement = Arrangement::kPacked;
  layout.offset = offset;
  layout.vertex_stride = vertex_stride ? vertex_stride : format_bytes(format);
  layout.instance_stride = instance_stride ? instance_stride : vertices * layout.vertex_stride;
  return layout;
}

std::size_t OutputLayout::required_bytes(const AttributeLayout& a, std::size_t instances,
                                         std::size_t vertices) {
  if (instances == 0 || vertices == 0) return a.offset;
  const std::string field = "outputs";
  const std::size_t last_instance = checked(instances - 1, a.instance_stride, a.offset, field);
  if (a.arrangement == Arrangement::kPlanes) {
    const std::size_t scalar = scalar_bytes(a.format);
    const std::size_t last_element = checked(2, a.plane_stride, vertices - 1, field);
    return checked(last_element, scalar, last_instance + scalar, field);
  }
  return checked(vertices - 1, a.vertex_stride, last_instance + format_bytes(a.format), field);
}

void validate_output_layout(const OutputLayout& layout, std::size_t instances, std::size_t vertices,
                            const std::uintptr_t buffer_ids[4]) {
  struct Named {
    const AttributeLayout* layout;  // null: not written
    const char* name;
    bool position;
  };
  const auto written = layout.written();
  const Named attributes[4] = {{written[0], "outputs.positions", true},
                               {written[1], "outputs.normals", false},
                               {written[2], "outputs.tangents", false},
                               {written[3], "outputs.previous_positions", true}};
  for (const Named& a : attributes) {
    if (a.layout) check_attribute(*a.layout, a.name, a.position, instances, vertices);
  }
  if (!buffer_ids) return;
  for (std::size_t x = 0; x < 4; ++x) {
    for (std::size_t y = x + 1; y < 4; ++y) {
      if (!attributes[x].layout || !attributes[y].layout || buffer_ids[x] != buffer_ids[y])
        continue;
      check_shared(*attributes[x].layout, attributes[x].name, *attributes[y].layout,
                   attributes[y].name, instances, vertices);
    }
  }
}

}  // namespace finflex

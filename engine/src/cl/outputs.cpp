#include "cl/outputs.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "cl/device_buffers.hpp"
#include "cl/host_pages.hpp"
#include "finflex/error.hpp"
#include "finflex/internal/cl_outputs.hpp"

namespace finflex {
namespace {

// kernels/common/outputs.cl's format numbers: finflex::AttributeFormat's order.
int format_number(AttributeFormat format) { return static_cast<int>(format); }

std::uint64_t next_serial() {
  static std::atomic<std::uint64_t> serial{1};
  return serial++;
}

}  // namespace

std::string output_build_options(const OutputLayout& layout) {
  auto attribute = [](const char* name, const AttributeLayout& a) {
    return std::string(" -DFF_") + name + "_FORMAT=" + std::to_string(format_number(a.format)) +
           " -DFF_" + name + "_PACKED=" + (a.arrangement == Arrangement::kPacked ? "1" : "0");
  };
  return attribute("POSITION", layout.positions) + attribute("NORMAL", layout.normals) +
         attribute("TANGENT", layout.tangent_layout) +
         attribute("PREVIOUS", layout.previous_layout) +
         " -DFF_TANGENTS=" + (layout.tangents ? "1" : "0") +
         " -DFF_PREVIOUS=" + (layout.previous_positions ? "1" : "0") +
         " -DFF_MESH_ORDER=" + (layout.order == VertexOrder::kMesh ? "1" : "0");
}

namespace detail {

namespace {

// Whether positions, normals (and tangents) are packed members that fill one vertex
// struct (the same vertex and instance strides, their bytes adding up to the stride,
// each on a 4-byte word), in slot order and without previous positions, each in a
// format `takes` accepts.
template <typename Takes>
bool fills_struct(const OutputLayout& l, Takes takes) {
  if (l.order != VertexOrder::kSlots || l.previous_positions) return false;
  // No allocation: ClDeformer asks this every frame (its work-item shape).
  const std::array<const AttributeLayout*, 3> all = {&l.positions, &l.normals, &l.tangent_layout};
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

}  // namespace

bool fills_vertex_struct(const OutputLayout& l) {
  return fills_struct(l, [](AttributeFormat f) { return f == AttributeFormat::kFloat32x3; });
}

namespace {

// The formats whose components kernels of more than one lane pack into 4-byte words.
bool word_format(AttributeFormat f) {
  return f == AttributeFormat::kFloat32x3 || f == AttributeFormat::kFloat32x4 ||
         f == AttributeFormat::kFloat16x4 || f == AttributeFormat::kSnorm16x4 ||
         f == AttributeFormat::kOctahedral16x2;
}

}  // namespace

bool fills_word_struct(const OutputLayout& l) { return fills_struct(l, word_format); }

bool in_one_buffer(const DeviceBatch& batch) {
  return batch.normals() == batch.positions() &&
         (!batch.outputs.tangents || batch.tangents() == batch.positions());
}

bool fills_own_arrays(const OutputLayout& l) {
  if (l.order != VertexOrder::kSlots || l.previous_positions) return false;
  // No allocation: ClDeformer asks this every frame (its work-item shape).
  const std::array<const AttributeLayout*, 3> all = {&l.positions, &l.normals, &l.tangent_layout};
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

}  // namespace detail

namespace {

// `flag`=1 and the struct's numbers (kernels/common/outputs.cl FF_STAGED_STRUCT: words
// of 4 bytes) for a vertex struct in one buffer that `fills` says the kernels take;
// empty for any other layout.
std::string vertex_struct_options(const DeviceBatch& batch, bool fills, const char* flag) {
  const OutputLayout& l = batch.outputs;
  if (!fills || !detail::in_one_buffer(batch)) return "";
  std::size_t start = std::min(l.positions.offset, l.normals.offset);
  if (l.tangents) start = std::min(start, l.tangent_layout.offset);
  auto floats_in = [&](const AttributeLayout& a) { return std::to_string((a.offset - start) / 4); };
  return std::string(" -D") + flag +
         "=1 -DFF_STAGED_FLOATS=" + std::to_string(l.positions.vertex_stride / 4) +
         " -DFF_STAGED_POSITION=" + floats_in(l.positions) +
         " -DFF_STAGED_NORMAL=" + floats_in(l.normals) +
         " -DFF_STAGED_TANGENT=" + (l.tangents ? floats_in(l.tangent_layout) : std::string("0"));
}

}  // namespace

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
  put(6, layout.tangent_layout);
  put(9, layout.previous_layout);
  out.s[12] = previous_valid ? 1 : 0;
  return out;
}

namespace detail {
namespace {

std::size_t buffer_bytes(const cl::Buffer& buffer) {
  std::size_t bytes = 0;
  if (buffer()) check_cl(buffer.getInfo(CL_MEM_SIZE, &bytes), "clGetMemObjectInfo");
  return bytes;
}

// The caller's memory a CL_MEM_USE_HOST_PTR buffer was made from (PoCL's kernels then
// write it as it is), else 0.
std::uintptr_t buffer_host_memory(const cl::Buffer& buffer) {
  void* host = nullptr;
  if (buffer()) check_cl(buffer.getInfo(CL_MEM_HOST_PTR, &host), "clGetMemObjectInfo");
  return reinterpret_cast<std::uintptr_t>(host);
}

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

// The attributes of a batch, in the kernels' order (positions, normals, tangents,
// previous positions), with their buffers and whether they are written.
template <typename Batch, typename Buffer>
struct Attribute {
  const char* name;
  const AttributeLayout* layout;
  Buffer* buffer;
  bool used;
};

template <typename Batch>
auto attributes_of(Batch& batch) {
  using Buffer = std::conditional_t<std::is_const_v<Batch>, const cl::Buffer, cl::Buffer>;
  const OutputLayout& o = batch.outputs;
  return std::array<Attribute<Batch, Buffer>, 4>{
      {{"positions", &o.positions, &batch.positions, true},
       {"normals", &o.normals, &batch.normals, true},
       {"tangents", &o.tangent_layout, &batch.tangents, o.tangents},
       {"previous_positions", &o.previous_layout, &batch.previous_positions,
        o.previous_positions}}};
}

// The index of the first attribute with the same host memory as attribute k (k itself
// when none before it has).
std::size_t first_with_memory(const DeviceBatch& batch, std::size_t k) {
  for (std::size_t earlier = 0; earlier < k; ++earlier) {
    if (batch.host[earlier] == batch.host[k]) return earlier;
  }
  return k;
}

// The kernels take a buffer for every attribute: a one-float stand-in for unused ones.
cl::Buffer placeholder(Context& context) {
  return make_buffer(context.context(), CL_MEM_READ_WRITE, sizeof(float));
}

DeviceBatch new_batch(Context& context, const BatchLayout& counts, const OutputLayout& outputs) {
  if (counts.instance_count == 0) {
    throw Error(ErrorCode::kInvalidArgument, "instances", "instances = 0: at least one is needed");
  }
  if (counts.instance_count > kMaxDeviceInstances) {
    throw Error(ErrorCode::kOutOfRange, "instances",
                "instances = " + std::to_string(counts.instance_count) + " is above the limit " +
                    std::to_string(kMaxDeviceInstances) +
                    " of one batch (the kernels count instances in 32 bits)");
  }
  DeviceBatch batch;
  batch.layout = counts;
  batch.outputs = outputs;
  batch.serial = next_serial();
  if (!outputs.tangents) batch.tangents = placeholder(context);
  if (!outputs.previous_positions) batch.previous_positions = placeholder(context);
  return batch;
}

// IEEE 754 binary16 to float (every class handled).
float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
  const std::uint32_t exponent = (h >> 10) & 0x1fu;
  const std::uint32_t mantissa = h & 0x3ffu;
  float magnitude;
  if (exponent == 0) {
    magnitude = std::ldexp(static_cast<float>(mantissa), -24);  // subnormal or zero
  } else if (exponent == 31) {
    magnitude =
        mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  } else {
    magnitude = std::ldexp(static_cast<float>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
  }
  return sign ? -magnitude : magnitude;
}

float snorm16_to_float(std::int16_t s) { return std::max(float(s) / 32767.0f, -1.0f); }

// The octahedral decoding (docs/handoff.md gives it in GLSL).
glm::vec3 octahedral_to_vector(float u, float v) {
  glm::vec3 n(u, v, 1.0f - std::fabs(u) - std::fabs(v));
  const float t = std::max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return glm::normalize(n);
}

// Element (i, v) of `a` from the raw bytes of its buffer.
glm::vec3 decode(const std::vector<unsigned char>& raw, const AttributeLayout& a, std::size_t i,
                 std::size_t v) {
  const std::size_t scalar = scalar_bytes(a.format);
  const bool packed = a.arrangement == Arrangement::kPacked;
  const std::size_t first =
      a.offset + i * a.instance_stride + (packed ? v * a.vertex_stride : v * scalar);
  const std::size_t apart = packed ? scalar : a.plane_stride * scalar;
  auto scalar_at = [&](std::size_t component, auto type) {
    decltype(type) value;
    std::memcpy(&value, raw.data() + first + component * apart, sizeof value);
    return value;
  };
  glm::vec3 out;
  switch (a.format) {
    case AttributeFormat::kFloat32x3:
    case AttributeFormat::kFloat32x4:
      for (int c = 0; c < 3; ++c) out[c] = scalar_at(std::size_t(c), float{});
      break;
    case AttributeFormat::kFloat16x3:
    case AttributeFormat::kFloat16x4:
      for (int c = 0; c < 3; ++c)
        out[c] = half_to_float(scalar_at(std::size_t(c), std::uint16_t{}));
      break;
    case AttributeFormat::kSnorm16x4:
      for (int c = 0; c < 3; ++c)
        out[c] = snorm16_to_float(scalar_at(std::size_t(c), std::int16_t{}));
      break;
    case AttributeFormat::kOctahedral16x2: {
      const std::uint32_t word = scalar_at(0, std::uint32_t{});
      out = octahedral_to_vector(snorm16_to_float(std::int16_t(word & 0xffffu)),
                                 snorm16_to_float(std::int16_t(word >> 16)));
      break;
    }
  }
  return out;
}

void read_attribute(Context& context, const cl::Buffer& buffer, const AttributeLayout& a,
                    const BatchLayout& planes, std::size_t vertices, std::vector<float>& out) {
  std::vector<unsigned char> raw(OutputLayout::required_bytes(a, planes.instance_count, vertices));
  check_cl(context.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, raw.size(), raw.data()),
           "clEnqueueReadBuffer outputs");
  for (std::size_t i = 0; i < planes.instance_count; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      const glm::vec3 value = decode(raw, a, i, v);
      for (int c = 0; c < 3; ++c) out[planes.index(i, c, v)] = value[c];
    }
  }
}

}  // namespace

OutputLayout planes_outputs(const BatchLayout& layout) {
  const AttributeFormat directions = layout.normal_format == NormalFormat::kHalf
                                         ? AttributeFormat::kFloat16x3
                                         : AttributeFormat::kFloat32x3;
  OutputLayout outputs;
  outputs.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, layout.plane_stride);
  outputs.normals = AttributeLayout::planes(directions, layout.plane_stride);
  outputs.tangents = layout.tangents;
  outputs.tangent_layout = AttributeLayout::planes(directions, layout.plane_stride);
  outputs.previous_layout = outputs.positions;
  return outputs;
}

namespace {

// `outputs` are FinFlex's planes of `counts`, normals (and tangents) in `format`.
bool writes_planes_in(const OutputLayout& outputs, const BatchLayout& counts, NormalFormat format) {
  BatchLayout in_format = counts;
  in_format.normal_format = format;
  const OutputLayout planes = planes_outputs(in_format);
  return outputs.order == VertexOrder::kSlots &&
         (!outputs.previous_positions || outputs.previous_layout == planes.positions) &&
         outputs.positions == planes.positions && outputs.normals == planes.normals &&
         outputs.tangents == planes.tangents &&
         (!outputs.tangents || outputs.tangent_layout == planes.tangent_layout);
}

}  // namespace

bool writes_finflex_planes(const OutputLayout& outputs, const BatchLayout& counts) {
  return writes_planes_in(outputs, counts, NormalFormat::kFloat32) ||
         writes_planes_in(outputs, counts, NormalFormat::kHalf);
}

std::string plane_stride_option(const OutputLayout& outputs, const BatchLayout& counts) {
  return writes_finflex_planes(outputs, counts)
             ? " -DFF_PLANE_STRIDE=" + std::to_string(counts.plane_stride) + "u"
             : "";
}

void check_outputs(const DeviceBatch& batch, std::size_t vertices, bool mesh_tangents,
                   const std::string& field) {
  const OutputLayout& outputs = batch.outputs;
  if (outputs.tangents && !mesh_tangents) fail(field + ".tangents", "the mesh has no tangents");
  const auto attributes = attributes_of(batch);
  std::uintptr_t ids[4];
  for (std::size_t k = 0; k < 4; ++k)
    ids[k] = reinterpret_cast<std::uintptr_t>((*attributes[k].buffer)());
  try {
    validate_output_layout(outputs, batch.layout.instance_count, vertices, ids);
  } catch (const Error& e) {
    // "outputs.normals..." under the caller's name for the batch.
    const std::string inner = e.field().rfind("outputs", 0) == 0 ? e.field().substr(7) : e.field();
    const std::string what = e.what();
    const std::string message =
        what.rfind(e.field(), 0) == 0 ? what.substr(e.field().size()) : ": " + what;
    throw Error(e.code(), field + inner, field + inner + message);
  }
  for (const auto& a : attributes) {
    if (!a.used) continue;
    const std::size_t need =
        OutputLayout::required_bytes(*a.layout, batch.layout.instance_count, vertices);
    const std::size_t have = buffer_bytes(*a.buffer);
    if (have < need) {
      fail(field + "." + a.name, "the buffer holds " + std::to_string(have) + " bytes, " +
                                     std::to_string(batch.layout.instance_count) +
                                     " instances of " + std::to_string(vertices) +
                                     " vertices in this layout need " + std::to_string(need));
    }
    // The kernels take every output buffer as floats and store whole scalars, or
    // vectors of them where the address is aligned to the vector
    // (kernels/cpu/lane_planes.cl): host memory must be aligned to a float.
    const std::uintptr_t host = buffer_host_memory(*a.buffer);
    if (host % sizeof(float) != 0) {
      fail(field + "." + a.name, "the buffer's host memory starts " +
                                     std::to_string(host % sizeof(float)) +
                                     " bytes past a multiple of 4 (the kernels take every "
                                     "output buffer as floats, whatever its format)");
    }
  }
}

DeviceBatch allocate_outputs(Context& context, const BatchLayout& counts,
                             const OutputLayout& outputs, std::size_t vertices) {
  if (outputs.tangents && !counts.tangents) fail("outputs.tangents", "the mesh has no tangents");
  DeviceBatch batch = new_batch(context, counts, outputs);
  validate_output_layout(outputs, counts.instance_count, vertices);
  const DeviceDescription& device = context.description();
  for (const auto& a : attributes_of(batch)) {
    if (!a.used) continue;
    const std::size_t bytes =
        OutputLayout::required_bytes(*a.layout, counts.instance_count, vertices);
    if (bytes > device.max_allocation_bytes) {
      throw Error(ErrorCode::kOutOfRange, "instances",
                  "instances = " + std::to_string(counts.instance_count) + " needs " +
                      std::to_string(bytes) + " bytes of " + a.name +
                      ", above the device's largest allocation (" +
                      std::to_string(device.max_allocation_bytes) + " bytes on '" +
                      device.device_name + "')");
    }
    *a.buffer = make_large_buffer(context, bytes);
  }
  return batch;
}

DeviceBatch bind_outputs(Context& context, const BatchLayout& counts, const OutputLayout& outputs,
                         const OutputBuffers& buffers, std::size_t vertices) {
  DeviceBatch batch = new_batch(context, counts, outputs);
  batch.positions = buffers.positions;
  batch.normals = buffers.normals;
  if (outputs.tangents) batch.tangents = buffers.tangents;
  if (outputs.previous_positions) batch.previous_positions = buffers.previous_positions;
  for (const auto& a : attributes_of(batch)) {
    if (a.used && !(*a.buffer)()) fail(std::string("outputs.") + a.name, "no buffer given");
  }
  check_outputs(batch, vertices, counts.tangents, "outputs");
  return batch;
}

DeviceBatch bind_host_outputs(Context& context, const BatchLayout& counts,
                              const OutputLayout& outputs, const HostOutputs& host,
                              std::size_t vertices) {
  DeviceBatch batch = new_batch(context, counts, outputs);
  const std::pair<void*, std::size_t> given[4] = {
      {host.positions, host.positions_bytes},
      {host.normals, host.normals_bytes},
      {outputs.tangents ? host.tangents : nullptr, host.tangents_bytes},
      {outputs.previous_positions ? host.previous_positions : nullptr,
       host.previous_positions_bytes}};
  const auto attributes = attributes_of(batch);
  for (std::size_t k = 0; k < 4; ++k) {
    if (!attributes[k].used) continue;
    const std::string field = std::string("outputs.") + attributes[k].name;
    if (!given[k].first || given[k].second == 0) fail(field, "no host memory given");
    cl::Buffer* buffer = attributes[k].buffer;
    for (std::size_t earlier = 0; earlier < k; ++earlier) {
      if (attributes[earlier].used && given[earlier].first == given[k].first) {
        if (given[earlier].second != given[k].second) {
          fail(field + "_bytes", "the same memory as " + std::string(attributes[earlier].name) +
                                     " with another size (" + std::to_string(given[k].second) +
                                     " bytes against " + std::to_string(given[earlier].second) +
                                     ")");
        }
        *buffer = *attributes[earlier].buffer;  // one buffer for interleaved attributes
      }
    }
    if (!(*buffer)()) {
      *buffer = make_buffer_over(context.context(), given[k].first, given[k].second);
    }
    batch.host[k] = given[k].first;
  }
  check_outputs(batch, vertices, counts.tangents, "outputs");
  return batch;
}

void map_host_outputs(Context& context, DeviceBatch& batch) {
  if (batch.host_mapped) return;
  const auto attributes = attributes_of(batch);
  for (std::size_t k = 0; k < 4; ++k) {
    if (!batch.host[k] || first_with_memory(batch, k) != k) continue;
    cl_int status = CL_SUCCESS;
    const std::size_t bytes = buffer_bytes(*attributes[k].buffer);
    context.queue().enqueueMapBuffer(*attributes[k].buffer, CL_TRUE, CL_MAP_READ, 0, bytes, nullptr,
                                     nullptr, &status);
    check_cl(status, "clEnqueueMapBuffer (host outputs)");
  }
  batch.host_mapped = true;
}

void unmap_host_outputs(Context& context, DeviceBatch& batch) {
  if (!batch.host_mapped) return;
  const auto attributes = attributes_of(batch);
  for (std::size_t k = 0; k < 4; ++k) {
    if (!batch.host[k] || first_with_memory(batch, k) != k) continue;
    // A buffer over host memory maps to that memory (OpenCL 1.2, clEnqueueMapBuffer).
    check_cl(context.queue().enqueueUnmapMemObject(*attributes[k].buffer, batch.host[k]),
             "clEnqueueUnmapMemObject (host outputs)");
  }
  batch.host_mapped = false;
}

DeformedBatch<float> read_outputs(Context& context, const DeviceBatch& batch,
                                  std::size_t vertices) {
  BatchLayout planes = batch.layout;
  planes.plane_stride = vertices;
  planes.normal_format = NormalFormat::kFloat32;
  planes.tangents = batch.outputs.tangents;
  DeformedBatch<float> out;
  out.resize(planes);
  const OutputLayout& o = batch.outputs;
  read_attribute(context, batch.positions, o.positions, planes, vertices, out.positions);
  read_attribute(context, batch.normals, o.normals, planes, vertices, out.normals);
  if (o.tangents)
    read_attribute(context, batch.tangents, o.tangent_layout, planes, vertices, out.tangents);
  if (o.previous_positions) {
    out.previous_positions.assign(planes.attribute_elements(), 0.0f);
    read_attribute(context, batch.previous_positions, o.previous_layout, planes, vertices,
                   out.previous_positions);
  }
  return out;
}

}  // namespace detail
}  // namespace finflex

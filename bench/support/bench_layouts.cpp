#include "bench_layouts.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace finflex::bench {
namespace {

// One vertex struct: position float32x3 at 0, then the normal and the tangent.
OutputLayout interleaved(AttributeFormat directions, bool tangents, std::size_t vertices) {
  const std::size_t direction_bytes = format_bytes(directions);
  const std::size_t stride = 12 + direction_bytes * (tangents ? 2 : 1);
  OutputLayout l;
  l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, stride, 0);
  l.normals = AttributeLayout::packed(directions, vertices, stride, 12);
  if (tangents)
    l.tangents = AttributeLayout::packed(directions, vertices, stride, 12 + direction_bytes);
  return l;
}

constexpr std::pair<LayoutKind, const char*> kLayoutNames[] = {
    {LayoutKind::kPlanes, "planes"},
    {LayoutKind::kInterleaved, "interleaved"},
    {LayoutKind::kCompact, "compact"},
    {LayoutKind::kSnorm, "snorm"},
    {LayoutKind::kArrays, "arrays"}};

}  // namespace

const char* to_string(LayoutKind kind) {
  for (const auto& [k, name] : kLayoutNames) {
    if (k == kind) return name;
  }
  return "planes";
}

std::optional<LayoutKind> layout_named(const std::string& name) {
  for (const auto& [kind, n] : kLayoutNames) {
    if (name == n) return kind;
  }
  return std::nullopt;
}

const char* layout_names() { return "planes, interleaved, compact, snorm or arrays"; }

BenchLayout bench_layout(const ClDeformer& deformer, NormalFormat format,
                         const OutputsChoice& choice) {
  BenchLayout out;
  const LayoutKind kind = choice.layout;
  const VertexOrder vertex_order = choice.order;
  out.vertices = deformer.output_vertices(vertex_order);
  const bool tangents = deformer.model().mesh().has_tangents();
  const bool half = format == NormalFormat::kHalf;
  if (kind == LayoutKind::kPlanes) {
    const std::size_t stride = padded_plane_stride(out.vertices);
    const AttributeFormat directions =
        half ? AttributeFormat::kFloat16x3 : AttributeFormat::kFloat32x3;
    out.layout.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, stride);
    out.layout.normals = AttributeLayout::planes(directions, stride);
    if (tangents) out.layout.tangents = AttributeLayout::planes(directions, stride);
  } else if (kind == LayoutKind::kArrays) {
    out.layout.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, out.vertices);
    out.layout.normals = AttributeLayout::packed(
        half ? AttributeFormat::kFloat16x4 : AttributeFormat::kFloat32x3, out.vertices);
    if (tangents) {
      out.layout.tangents = AttributeLayout::packed(
          half ? AttributeFormat::kFloat16x4 : AttributeFormat::kFloat32x4, out.vertices);
    }
  } else if (kind == LayoutKind::kInterleaved) {
    out.layout = interleaved(half ? AttributeFormat::kFloat16x4 : AttributeFormat::kFloat32x3,
                             tangents, out.vertices);
  } else if (kind == LayoutKind::kCompact) {
    out.layout = interleaved(AttributeFormat::kOctahedral16x2, tangents, out.vertices);
  } else {  // kSnorm
    out.layout = interleaved(AttributeFormat::kSnorm16x4, tangents, out.vertices);
  }
  out.one_buffer = kind != LayoutKind::kPlanes && kind != LayoutKind::kArrays;
  out.host = choice.host;
  out.layout.order = vertex_order;
  if (choice.previous) {
    out.layout.previous_positions =
        AttributeLayout::planes(AttributeFormat::kFloat32x3, padded_plane_stride(out.vertices));
  }
  return out;
}

namespace {

void* host_block(HostMemory& memory, std::size_t bytes) {
  const std::size_t rounded = (bytes + 63) / 64 * 64;
  void* block = std::aligned_alloc(64, rounded);
  if (block == nullptr) throw Error(ErrorCode::kOutOfRange, "host", "host: out of host memory");
  memory.blocks.emplace_back(static_cast<unsigned char*>(block), std::free);
  return block;
}

// Every attribute in its own host block (planes, arrays), or one block for the vertex
// struct.
DeviceBatch bind_host_batch(ClDeformer& deformer, std::size_t instances, const BenchLayout& layout,
                            HostMemory& memory) {
  const OutputLayout& l = layout.layout;
  const std::size_t n = layout.vertices;
  HostOutputs host;
  auto bytes_of = [&](const AttributeLayout& a) {
    return OutputLayout::required_bytes(a, instances, n);
  };
  if (!layout.one_buffer) {
    host.positions_bytes = bytes_of(l.positions);
    host.positions = host_block(memory, host.positions_bytes);
    host.normals_bytes = bytes_of(l.normals);
    host.normals = host_block(memory, host.normals_bytes);
    if (l.tangents) {
      host.tangents_bytes = bytes_of(*l.tangents);
      host.tangents = host_block(memory, host.tangents_bytes);
    }
  } else {
    std::size_t bytes = std::max(bytes_of(l.positions), bytes_of(l.normals));
    if (l.tangents) bytes = std::max(bytes, bytes_of(*l.tangents));
    void* block = host_block(memory, bytes);
    host.positions = host.normals = block;
    host.positions_bytes = host.normals_bytes = bytes;
    if (l.tangents) {
      host.tangents = block;
      host.tangents_bytes = bytes;
    }
  }
  if (l.previous_positions) {
    host.previous_positions_bytes = bytes_of(*l.previous_positions);
    host.previous_positions = host_block(memory, host.previous_positions_bytes);
  }
  return deformer.bind_host(instances, l, host);
}

}  // namespace

DeviceBatch make_bench_batch(ClDeformer& deformer, std::size_t instances, const BenchLayout& layout,
                             HostMemory& memory) {
  const OutputLayout& l = layout.layout;
  if (layout.host) return bind_host_batch(deformer, instances, layout, memory);
  if (!layout.one_buffer) return deformer.allocate(instances, l);
  // One buffer for the vertex struct, up to its last attribute's end.
  std::size_t bytes = OutputLayout::required_bytes(l.normals, instances, layout.vertices);
  if (l.tangents) {
    bytes = std::max(bytes, OutputLayout::required_bytes(*l.tangents, instances, layout.vertices));
  }
  cl_int status = CL_SUCCESS;
  cl::Buffer vertices(deformer.context().context(), CL_MEM_READ_WRITE, bytes, nullptr, &status);
  check_cl(status, "clCreateBuffer");
  OutputBuffers buffers{vertices, vertices, vertices, {}};
  if (l.previous_positions) {
    buffers.previous_positions =
        cl::Buffer(deformer.context().context(), CL_MEM_READ_WRITE,
                   OutputLayout::required_bytes(*l.previous_positions, instances, layout.vertices),
                   nullptr, &status);
    check_cl(status, "clCreateBuffer");
  }
  return deformer.bind(instances, l, buffers);
}

}  // namespace finflex::bench

#include "cl/output_buffers.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "cl/device_buffers.hpp"
#include "cl/host_pages.hpp"
#include "finflex/error.hpp"

namespace finflex::detail {
namespace {

std::uint64_t next_serial() {
  static std::atomic<std::uint64_t> serial{1};
  return serial++;
}

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
  const AttributeLayout* layout;  // null: not written
  Buffer* buffer;
  bool used() const { return layout != nullptr; }
};

template <typename Batch>
auto attributes_of(Batch& batch) {
  using Buffer = std::conditional_t<std::is_const_v<Batch>, const cl::Buffer, cl::Buffer>;
  const auto written = batch.outputs.written();
  return std::array<Attribute<Batch, Buffer>, 4>{
      {{"positions", written[0], &batch.positions},
       {"normals", written[1], &batch.normals},
       {"tangents", written[2], &batch.tangents},
       {"previous_positions", written[3], &batch.previous_positions}}};
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

DeviceBatch new_batch(Context& context, const BatchShape& counts, const OutputLayout& outputs) {
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
  batch.shape = counts;
  batch.outputs = outputs;
  batch.serial = next_serial();
  if (!outputs.tangents) batch.tangents = placeholder(context);
  if (!outputs.previous_positions) batch.previous_positions = placeholder(context);
  return batch;
}

}  // namespace

void check_outputs(const DeviceBatch& batch, std::size_t vertices, bool mesh_tangents,
                   const std::string& field) {
  const OutputLayout& outputs = batch.outputs;
  if (outputs.tangents && !mesh_tangents) fail(field + ".tangents", "the mesh has no tangents");
  const auto attributes = attributes_of(batch);
  std::uintptr_t ids[4];
  for (std::size_t k = 0; k < 4; ++k)
    ids[k] = reinterpret_cast<std::uintptr_t>((*attributes[k].buffer)());
  try {
    validate_output_layout(outputs, batch.shape.instance_count, vertices, ids);
  } catch (const Error& e) {
    // "outputs.normals..." under the caller's name for the batch.
    const std::string inner = e.field().rfind("outputs", 0) == 0 ? e.field().substr(7) : e.field();
    const std::string what = e.what();
    const std::string message =
        what.rfind(e.field(), 0) == 0 ? what.substr(e.field().size()) : ": " + what;
    throw Error(e.code(), field + inner, field + inner + message);
  }
  for (const auto& a : attributes) {
    if (!a.used()) continue;
    const std::size_t need =
        OutputLayout::required_bytes(*a.layout, batch.shape.instance_count, vertices);
    const std::size_t have = buffer_bytes(*a.buffer);
    if (have < need) {
      fail(field + "." + a.name, "the buffer holds " + std::to_string(have) + " bytes, " +
                                     std::to_string(batch.shape.instance_count) + " instances of " +
                                     std::to_string(vertices) + " vertices in this layout need " +
                                     std::to_string(need));
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

DeviceBatch allocate_outputs(Context& context, const BatchShape& counts,
                             const OutputLayout& outputs, std::size_t vertices) {
  if (outputs.tangents && !counts.tangents) fail("outputs.tangents", "the mesh has no tangents");
  DeviceBatch batch = new_batch(context, counts, outputs);
  validate_output_layout(outputs, counts.instance_count, vertices);
  const DeviceDescription& device = context.description();
  for (const auto& a : attributes_of(batch)) {
    if (!a.used()) continue;
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

DeviceBatch bind_outputs(Context& context, const BatchShape& counts, const OutputLayout& outputs,
                         const OutputBuffers& buffers, std::size_t vertices) {
  DeviceBatch batch = new_batch(context, counts, outputs);
  batch.positions = buffers.positions;
  batch.normals = buffers.normals;
  if (outputs.tangents) batch.tangents = buffers.tangents;
  if (outputs.previous_positions) batch.previous_positions = buffers.previous_positions;
  for (const auto& a : attributes_of(batch)) {
    if (a.used() && !(*a.buffer)()) fail(std::string("outputs.") + a.name, "no buffer given");
  }
  check_outputs(batch, vertices, counts.tangents, "outputs");
  return batch;
}

DeviceBatch bind_host_outputs(Context& context, const BatchShape& counts,
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
    if (!attributes[k].used()) continue;
    const std::string field = std::string("outputs.") + attributes[k].name;
    if (!given[k].first || given[k].second == 0) fail(field, "no host memory given");
    cl::Buffer* buffer = attributes[k].buffer;
    for (std::size_t earlier = 0; earlier < k; ++earlier) {
      if (attributes[earlier].used() && given[earlier].first == given[k].first) {
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

}  // namespace finflex::detail

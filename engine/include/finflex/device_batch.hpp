// The outputs of one batch on an OpenCL device, written every frame: positions,
// normals, tangents (when the mesh has them) and, when asked for, the previous frame's
// positions, each where and how its OutputLayout descriptor says
// (finflex/output_layout.hpp). ClDeformer::allocate gives FinFlex's own
// structure-of-arrays planes (finflex/batch.hpp); ClDeformer::bind takes the caller's
// buffers in any layout, ClDeformer::bind_host the caller's host memory.
//
// Memory of the default planes, per instance and vertex slot: positions 12 bytes;
// normals 12 (float32) or 6 (IEEE half, NormalFormat::kHalf); tangents the same again
// when the mesh has them. 4,000 instances of the 10,786-vertex fish (10,816 slots)
// with float32 normals: 4,000 * 10,816 * 24 B = 1.04 GB.
//
// Thread-safety: a batch is written by the frames enqueued into it; give each thread
// its own batch (finflex/cl_deformer.hpp). Its buffers may be read on any thread once
// the frame's event is complete.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/output_layout.hpp"

namespace finflex {

// Most instances in one batch: the kernels count instances in 32 bits
// (ClDeformer::allocate refuses more, as it refuses more than the device can allocate).
constexpr std::size_t kMaxDeviceInstances = 0xffffffffu;

struct DeviceBatch {
  // The counts: instances, the mesh's vertices, whether the mesh has tangents; for the
  // default planes also their stride and the normals' format (as DeformedBatch reads).
  BatchShape shape;
  // Where each attribute goes (ClDeformer::allocate: the planes of `shape`).
  OutputLayout outputs;
  cl::Buffer positions;
  cl::Buffer normals;
  cl::Buffer tangents;            // a one-value placeholder when not written
  cl::Buffer previous_positions;  // likewise
  // Identifies these buffers (set by ClDeformer::allocate, bind and bind_host, unique in
  // the process; 0: none), so a deformer sets kernel arguments only when a frame goes
  // to another batch and checks a batch once. Replace a batch by making a new one,
  // never by assigning its buffers.
  std::uint64_t serial = 0;
  // The model (RiggedMesh::id) whose deformer made it: its vertex slots are that
  // deformer's, so only that model's jobs may write it.
  std::uint64_t model_id = 0;
  // Frames written to the batch: from the second on, previous_positions holds the
  // frame before (the first frame writes its own positions there: no motion).
  std::uint64_t frames_written = 0;
  // With ClDeformer::bind_host: the caller's memory behind positions, normals,
  // tangents and previous_positions (null where not given), and whether the buffers
  // are mapped for the host (ClDeformer::map_host) now.
  std::array<void*, 4> host{};
  bool host_mapped = false;
};

// The caller's device buffers for ClDeformer::bind; one buffer may hold several
// attributes (an interleaved vertex struct): pass it for each.
struct OutputBuffers {
  cl::Buffer positions;
  cl::Buffer normals;
  cl::Buffer tangents;
  cl::Buffer previous_positions;
};

// The caller's host memory for ClDeformer::bind_host: a pointer and its size in bytes
// per attribute (the same pointer for attributes interleaved in one array). On CPU
// devices the kernels write into it directly (CL_MEM_USE_HOST_PTR; keep it aligned to
// 64 bytes, or the OpenCL implementation may copy; memory not aligned to 4 bytes is
// refused: the kernels take every output buffer as floats); on GPUs the driver copies it
// back when it is mapped (docs/handoff.md measures both).
struct HostOutputs {
  void* positions = nullptr;
  std::size_t positions_bytes = 0;
  void* normals = nullptr;
  std::size_t normals_bytes = 0;
  void* tangents = nullptr;
  std::size_t tangents_bytes = 0;
  void* previous_positions = nullptr;
  std::size_t previous_positions_bytes = 0;
};

}  // namespace finflex

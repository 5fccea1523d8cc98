// The outputs of one batch on an OpenCL device: positions, normals and tangents of
// every instance in the structure-of-arrays planes of finflex/batch.hpp, in buffers
// allocated once (ClDeformer::allocate) and written every frame.
//
// Memory, per instance and vertex slot: positions 12 bytes; normals 12 (float32) or 6
// (IEEE half, NormalFormat::kHalf); tangents the same again when the mesh has them.
// 4,000 instances of the 10,786-vertex fish (10,816 slots) with float32 normals:
// 4,000 * 10,816 * 24 B = 1.04 GB.
//
// Thread-safety: a batch is written by the frames enqueued into it; give each thread
// its own batch (finflex/cl_deformer.hpp). Its buffers may be read on any thread once
// the frame's event is complete.
#pragma once

#include <cstddef>
#include <cstdint>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"

namespace finflex {

// Most instances in one batch: the kernels count instances in 32 bits
// (ClDeformer::allocate refuses more, as it refuses more than the device can allocate).
constexpr std::size_t kMaxDeviceInstances = 0xffffffffu;

struct DeviceBatch {
  BatchLayout layout;
  cl::Buffer positions;  // layout.attribute_elements() float32 values
  cl::Buffer normals;    // layout.attribute_elements() values in layout.normal_format
  cl::Buffer tangents;   // the same; a one-value placeholder when the mesh has none
  // Identifies these buffers (set by ClDeformer::allocate, unique in the process; 0:
  // none), so a deformer sets kernel arguments only when a frame goes to another
  // batch. Replace a batch by allocating a new one, never by assigning its buffers.
  std::uint64_t serial = 0;
};

}  // namespace finflex

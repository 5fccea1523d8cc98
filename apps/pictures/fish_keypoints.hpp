// The world positions of a few chosen vertices (slots) of every instance of a batch,
// read from the device each frame: one gather kernel packs them (finflex/batch.hpp:
// element (i, c, s) at (3 i + c) plane_stride + s) and one contiguous read brings them
// back, 12 bytes per instance and slot. (A rectangular read per slot, one float per
// instance row, costs the driver a copy per row: tens of milliseconds a frame for
// 1,000 fish on a GPU.)
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/finflex.hpp"

namespace finflex::pictures {

class SlotPositionReader {
 public:
  // Reads `slots` of batches of `instances` instances and `plane_stride` on `context`'s
  // device. kInvalidArgument naming "slot" when one is not below the plane stride.
  SlotPositionReader(Context& context, std::vector<std::uint32_t> slots, std::size_t instances,
                     std::size_t plane_stride);

  // Per slot (in the constructor's order), per instance: its position in `batch` once
  // the work queued before on `queue` is done. Blocking. kInvalidArgument naming
  // "batch" when its shape is not the constructor's; kOpenCL when a launch or the read
  // fails.
  std::vector<std::vector<glm::vec3>> read(cl::CommandQueue& queue, const DeviceBatch& batch);

 private:
  std::size_t instances_;
  std::size_t plane_stride_;
  std::size_t slot_count_;
  cl::Kernel kernel_;
  cl::Buffer slots_;
  cl::Buffer packed_;
  std::vector<float> host_;
};

}  // namespace finflex::pictures

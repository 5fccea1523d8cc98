// The world positions of a few chosen vertices of every instance of a batch, read
// straight from the device: one rectangular read per vertex, its x, y and z planes of
// all instances (finflex/batch.hpp: element (i, c, s) at (3 i + c) plane_stride + s).
// Bytes moved: 12 per instance and vertex.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/finflex.hpp"

namespace finflex::pictures {

// Positions of slot `slot` of every instance, in instance order. Blocking (waits for
// the work queued before it). kOpenCL on a failed read; kInvalidArgument naming
// "slot" when it is not below the batch's plane stride.
std::vector<glm::vec3> read_slot_positions(cl::CommandQueue& queue, const DeviceBatch& batch,
                                           std::uint32_t slot);

}  // namespace finflex::pictures

#include "fish_keypoints.hpp"

#include <string>

namespace finflex::pictures {

std::vector<glm::vec3> read_slot_positions(cl::CommandQueue& queue, const DeviceBatch& batch,
                                           std::uint32_t slot) {
  const BatchShape& layout = batch.shape;
  if (slot >= layout.plane_stride) {
    throw Error(ErrorCode::kInvalidArgument, "slot",
                "slot " + std::to_string(slot) + " is not below the plane stride " +
                    std::to_string(layout.plane_stride));
  }
  // A rectangle one float wide and 3 N rows high, one row per plane.
  const std::size_t rows = 3 * layout.instance_count;
  std::vector<float> values(rows);
  const cl_int status = queue.enqueueReadBufferRect(
      batch.positions, CL_TRUE, {slot * sizeof(float), 0, 0}, {0, 0, 0}, {sizeof(float), rows, 1},
      layout.plane_stride * sizeof(float), 0, sizeof(float), 0, values.data());
  if (status != CL_SUCCESS) {
    throw Error(ErrorCode::kOpenCL, "positions",
                "reading vertex positions failed (OpenCL error " + std::to_string(status) + ")");
  }
  std::vector<glm::vec3> positions(layout.instance_count);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    positions[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  }
  return positions;
}

}  // namespace finflex::pictures

#include "fish_keypoints.hpp"

#include <algorithm>
#include <string>

namespace finflex::pictures {
namespace {

constexpr std::size_t kGroup = 64;  // work-items per group along the instances

const char* const kGatherSource = R"CLC(
/* packed[3 (k instances + i) + c] = positions[(3 i + c) plane_stride + slots[k]]. */
__kernel void gather_slot_positions(__global const float* restrict positions,
                                    const uint plane_stride, const uint instances,
                                    __global const uint* restrict slots, const uint slot_count,
                                    __global float* restrict packed) {
  const uint i = get_global_id(0);
  const uint k = get_global_id(1);
  if (i >= instances || k >= slot_count) return;
  const size_t slot = slots[k];
  __global float* out = packed + 3 * ((size_t)k * instances + i);
  for (uint c = 0; c < 3; ++c) out[c] = positions[(3 * (size_t)i + c) * plane_stride + slot];
}
)CLC";

void check(cl_int status, const char* what) {
  if (status != CL_SUCCESS) {
    throw Error(ErrorCode::kOpenCL, "positions",
                std::string(what) + " failed (OpenCL error " + std::to_string(status) + ")");
  }
}

}  // namespace

SlotPositionReader::SlotPositionReader(Context& context, std::vector<std::uint32_t> slots,
                                       std::size_t instances, std::size_t plane_stride)
    : instances_(instances), plane_stride_(plane_stride), slot_count_(slots.size()) {
  for (std::uint32_t slot : slots) {
    if (slot >= plane_stride) {
      throw Error(ErrorCode::kInvalidArgument, "slot",
                  "slot " + std::to_string(slot) + " is not below the plane stride " +
                      std::to_string(plane_stride));
    }
  }
  if (slot_count_ == 0 || instances_ == 0) return;
  kernel_ = context.kernel("gather_slot_positions", ProgramSource{{}, "", kGatherSource}, "");
  cl_int status = CL_SUCCESS;
  slots_ = cl::Buffer(context.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                      slots.size() * sizeof(std::uint32_t), slots.data(), &status);
  check(status, "clCreateBuffer (slots)");
  host_.resize(3 * slot_count_ * instances_);
  packed_ = cl::Buffer(context.context(), CL_MEM_WRITE_ONLY, host_.size() * sizeof(float), nullptr,
                       &status);
  check(status, "clCreateBuffer (packed positions)");
}

std::vector<std::vector<glm::vec3>> SlotPositionReader::read(cl::CommandQueue& queue,
                                                             const DeviceBatch& batch) {
  if (batch.shape.instance_count != instances_ || batch.shape.plane_stride != plane_stride_) {
    throw Error(ErrorCode::kInvalidArgument, "batch",
                "batch: " + std::to_string(batch.shape.instance_count) +
                    " instances and plane stride " + std::to_string(batch.shape.plane_stride) +
                    ", the reader was made for " + std::to_string(instances_) + " and " +
                    std::to_string(plane_stride_));
  }
  std::vector<std::vector<glm::vec3>> out(slot_count_);
  if (slot_count_ == 0 || instances_ == 0) return out;
  kernel_.setArg(0, batch.positions);
  kernel_.setArg(1, static_cast<cl_uint>(plane_stride_));
  kernel_.setArg(2, static_cast<cl_uint>(instances_));
  kernel_.setArg(3, slots_);
  kernel_.setArg(4, static_cast<cl_uint>(slot_count_));
  kernel_.setArg(5, packed_);
  const std::size_t across = (instances_ + kGroup - 1) / kGroup * kGroup;
  check(queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(across, slot_count_),
                                   cl::NDRange(kGroup, 1)),
        "gathering vertex positions");
  check(queue.enqueueReadBuffer(packed_, CL_TRUE, 0, host_.size() * sizeof(float), host_.data()),
        "reading vertex positions");
  for (std::size_t k = 0; k < slot_count_; ++k) {
    out[k].resize(instances_);
    const float* row = host_.data() + 3 * k * instances_;
    for (std::size_t i = 0; i < instances_; ++i) {
      out[k][i] = {row[3 * i], row[3 * i + 1], row[3 * i + 2]};
    }
  }
  return out;
}

}  // namespace finflex::pictures

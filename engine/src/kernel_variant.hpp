// The build options that specialise a deformation kernel, as one key: kernels are
// looked up by it every frame (no strings built) and built with options() once.
#pragma once

#include <cstddef>
#include <string>
#include <tuple>

#include "finflex/batch.hpp"
#include "finflex/job.hpp"

namespace finflex::detail {

struct KernelVariant {
  std::size_t kernel = 0;  // which kernel of the program (the deformer's numbering)
  NormalMode normals = NormalMode::kRotate;
  NormalFormat format = NormalFormat::kFloat32;
  bool tangents = false;
  std::size_t instances_per_item = 1;
  bool placement = false;  // world placement as the last stage
  std::size_t lanes = 1;   // vertex slots per work-item (kernels/common/lanes.cl)
  bool streaming_stores = false;  // with lanes: kernels/cpu/lane_planes.cl

  bool operator<(const KernelVariant& other) const {
    return std::tie(kernel, normals, format, tangents, instances_per_item, placement, lanes,
                    streaming_stores) <
           std::tie(other.kernel, other.normals, other.format, other.tangents,
                    other.instances_per_item, other.placement, other.lanes, other.streaming_stores);
  }

  // -D options of kernels/common/secant.cl, planes.cl, placement.cl, lanes.cl and
  // cpu/lane_planes.cl (one lane is the default: one-lane builds keep the options they
  // always had).
  std::string options() const {
    return std::string("-DFF_NORMALS_JACOBIAN=") + (normals == NormalMode::kJacobian ? "1" : "0") +
           " -DFF_TANGENTS=" + (tangents ? "1" : "0") +
           " -DFF_HALF_NORMALS=" + (format == NormalFormat::kHalf ? "1" : "0") +
           " -DFF_INSTANCES_PER_ITEM=" + std::to_string(instances_per_item) +
           " -DFF_PLACEMENT=" + (placement ? "1" : "0") +
           (lanes > 1 ? " -DFF_LANES=" + std::to_string(lanes) : std::string()) +
           (lanes > 1 ? std::string(" -DFF_STREAMING_STORES=") + (streaming_stores ? "1" : "0")
                      : std::string());
  }
};

}  // namespace finflex::detail

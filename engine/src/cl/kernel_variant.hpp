// The build options that specialise a deformation kernel, as one key: kernels are
// looked up by it every frame and built with options() once.
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
  std::string outputs;  // output_build_options() of the batch's OutputLayout
  std::size_t instances_per_item = 1;
  bool placement = false;         // world placement as the last stage
  std::size_t lanes = 1;          // vertex slots per work-item (kernels/common/lanes.cl)
  bool streaming_stores = false;  // with lanes: kernels/cpu/lane_planes.cl
  bool instance_list = false;     // kernels/common/instance_list.cl

  bool operator<(const KernelVariant& other) const {
    return std::tie(kernel, normals, outputs, instances_per_item, placement, lanes,
                    streaming_stores, instance_list) <
           std::tie(other.kernel, other.normals, other.outputs, other.instances_per_item,
                    other.placement, other.lanes, other.streaming_stores, other.instance_list);
  }

  // -D options of kernels/common/secant.cl, planes.cl, outputs.cl, placement.cl,
  // lanes.cl, instance_list.cl and cpu/lane_planes.cl (one lane and no list are the
  // defaults: such builds keep the options they always had).
  std::string options() const {
    return std::string("-DFF_NORMALS_JACOBIAN=") + (normals == NormalMode::kJacobian ? "1" : "0") +
           outputs + " -DFF_INSTANCES_PER_ITEM=" + std::to_string(instances_per_item) +
           " -DFF_PLACEMENT=" + (placement ? "1" : "0") +
           (lanes > 1 ? " -DFF_LANES=" + std::to_string(lanes) : std::string()) +
           (lanes > 1 ? std::string(" -DFF_STREAMING_STORES=") + (streaming_stores ? "1" : "0")
                      : std::string()) +
           (instance_list ? " -DFF_INSTANCE_LIST=1" : "");
  }
};

}  // namespace finflex::detail

// The OpenCL C sources under kernels/, embedded at build time (cmake/embed_kernels.cmake).
#pragma once

#include <string>
#include <vector>

namespace finflex::detail {

struct KernelSource {
  std::string file_name;  // its path under kernels/, e.g. "deformers/bend.cl"
  std::string text;
};

// In build order: shared functions first, entry points last.
const std::vector<KernelSource>& kernel_sources();

}  // namespace finflex::detail

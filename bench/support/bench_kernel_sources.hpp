// The benchmarks' own OpenCL files (bench/kernels/), embedded at build time.
#pragma once

#include <string>
#include <vector>

namespace finflex::bench {

struct KernelSource {
  std::string file_name;  // its path under bench/kernels/
  std::string text;
};

const std::vector<KernelSource>& bench_kernel_sources();

}  // namespace finflex::bench

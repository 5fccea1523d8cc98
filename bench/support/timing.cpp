#include "timing.hpp"

#include <algorithm>

#include "finflex/context.hpp"

namespace finflex::bench {

double span_seconds(const cl::Event& first, const cl::Event& last) {
  check_cl(last.wait(), "clWaitForEvents");
  const cl_ulong start = first.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = last.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-9;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  if (n == 0) return 0.0;
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<double> FrameTimes::kernel_medians() const {
  std::vector<double> medians;
  for (std::size_t k = 0; !kernels.empty() && k < kernels.front().size(); ++k) {
    std::vector<double> values;
    for (const std::vector<double>& frame : kernels) {
      if (k < frame.size()) values.push_back(frame[k]);
    }
    medians.push_back(median(values));
  }
  return medians;
}

}  // namespace finflex::bench

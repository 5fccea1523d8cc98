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

}  // namespace finflex::bench

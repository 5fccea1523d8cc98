// Large buffers of CPU devices in transparent huge pages.
#pragma once

#include <cstddef>

#include <CL/opencl.hpp>

#include "finflex/context.hpp"

namespace finflex::detail {

// The size of a huge page on x86-64 and AArch64 Linux (2 MiB), and the smallest buffer
// make_large_buffer gives huge pages.
constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// A read-write buffer of `bytes` for the kernels' outputs or scratch sets (uninitialised;
// kOpenCL on failure). On a CPU device (PoCL), where a buffer's memory is the host's, a
// buffer of at least kHugePageBytes is host memory aligned to a huge page and advised to
// the kernel as huge-page memory (Linux madvise MADV_HUGEPAGE), wrapped with
// CL_MEM_USE_HOST_PTR (make_buffer_over) and freed by the buffer's destructor callback:
// the deformation's stores, which visit dozens of planes' pages a work-group, then cross
// far fewer pages (docs/benchmarks.md#choice-huge-page-outputs). Elsewhere, or
// where such memory cannot be had, an ordinary buffer.
cl::Buffer make_large_buffer(const Context& context, std::size_t bytes);

}  // namespace finflex::detail

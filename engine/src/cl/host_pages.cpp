#include "cl/host_pages.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "cl/device_buffers.hpp"

namespace finflex::detail {

namespace {

// The destructor callback of a buffer over make_large_buffer's memory: the buffer is
// gone, and with it the device's last use of the memory.
void CL_CALLBACK free_host_memory(cl_mem, void* memory) { std::free(memory); }

// Memory of `bytes` aligned to a huge page and advised as huge-page memory; null where
// it cannot be had.
void* huge_page_memory(std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  void* memory = nullptr;
  if (posix_memalign(&memory, kHugePageBytes, bytes) != 0) return nullptr;
  // Advice only: with huge pages off (transparent_hugepage "never") the memory stays
  // in small pages, and works the same.
  madvise(memory, bytes, MADV_HUGEPAGE);
  return memory;
#else
  (void)bytes;
  return nullptr;
#endif
}

}  // namespace

cl::Buffer make_large_buffer(const Context& context, std::size_t bytes) {
  void* memory = context.description().type == "CPU" && bytes >= kHugePageBytes
                     ? huge_page_memory(bytes)
                     : nullptr;
  if (!memory) return make_buffer(context.context(), CL_MEM_READ_WRITE, bytes);
  cl::Buffer buffer;
  try {
    buffer = make_buffer_over(context.context(), memory, bytes);
  } catch (...) {
    std::free(memory);
    throw;
  }
  if (clSetMemObjectDestructorCallback(buffer(), free_host_memory, memory) != CL_SUCCESS) {
    // Nothing else holds the buffer yet: releasing it ends the device's use of the
    // memory at once.
    buffer = cl::Buffer();
    std::free(memory);
    return make_buffer(context.context(), CL_MEM_READ_WRITE, bytes);
  }
  return buffer;
}

}  // namespace finflex::detail

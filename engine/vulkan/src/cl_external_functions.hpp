// OpenCL's external-memory and semaphore entry points (cl_khr_external_memory,
// cl_khr_external_semaphore; clCreateBufferWithProperties is OpenCL 3.0), resolved at
// run time so that FinFlex still builds against OpenCL 1.2 headers and runs with a
// loader or platform that lacks them.
#pragma once

#include <string>

#include <CL/cl.h>
#include <CL/cl_ext.h>

namespace finflex::detail {

struct ClExternalFunctions {
  using CreateBufferWithProperties = cl_mem(CL_API_CALL*)(cl_context, const cl_ulong*, cl_mem_flags,
                                                          size_t, void*, cl_int*);
  CreateBufferWithProperties create_buffer_with_properties = nullptr;
  clEnqueueAcquireExternalMemObjectsKHR_fn acquire = nullptr;
  clEnqueueReleaseExternalMemObjectsKHR_fn release = nullptr;
  clCreateSemaphoreWithPropertiesKHR_fn create_semaphore = nullptr;
  clEnqueueWaitSemaphoresKHR_fn wait_semaphores = nullptr;
  clEnqueueSignalSemaphoresKHR_fn signal_semaphores = nullptr;
  clReleaseSemaphoreKHR_fn release_semaphore = nullptr;

  bool has_memory() const { return create_buffer_with_properties && acquire && release; }
  bool has_semaphores() const {
    return create_semaphore && wait_semaphores && signal_semaphores && release_semaphore;
  }
};

// The entry points of `platform` (null where missing).
ClExternalFunctions load_cl_external_functions(cl_platform_id platform);

}  // namespace finflex::detail

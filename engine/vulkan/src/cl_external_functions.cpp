#include "cl_external_functions.hpp"

#include <dlfcn.h>

namespace finflex::detail {

ClExternalFunctions load_cl_external_functions(cl_platform_id platform) {
  ClExternalFunctions f;
  // A core OpenCL 3.0 function: the loader's, where it has it.
  f.create_buffer_with_properties =
      reinterpret_cast<ClExternalFunctions::CreateBufferWithProperties>(
          dlsym(RTLD_DEFAULT, "clCreateBufferWithProperties"));
  const auto get = [platform](const char* name) {
    return clGetExtensionFunctionAddressForPlatform(platform, name);
  };
  f.acquire = reinterpret_cast<clEnqueueAcquireExternalMemObjectsKHR_fn>(
      get("clEnqueueAcquireExternalMemObjectsKHR"));
  f.release = reinterpret_cast<clEnqueueReleaseExternalMemObjectsKHR_fn>(
      get("clEnqueueReleaseExternalMemObjectsKHR"));
  f.create_semaphore = reinterpret_cast<clCreateSemaphoreWithPropertiesKHR_fn>(
      get("clCreateSemaphoreWithPropertiesKHR"));
  f.wait_semaphores =
      reinterpret_cast<clEnqueueWaitSemaphoresKHR_fn>(get("clEnqueueWaitSemaphoresKHR"));
  f.signal_semaphores =
      reinterpret_cast<clEnqueueSignalSemaphoresKHR_fn>(get("clEnqueueSignalSemaphoresKHR"));
  f.release_semaphore = reinterpret_cast<clReleaseSemaphoreKHR_fn>(get("clReleaseSemaphoreKHR"));
  return f;
}

}  // namespace finflex::detail

// finflex info: the OpenCL platforms and devices, which one is the default, and the
// extensions each offers for handing outputs to a renderer (docs/handoff.md).
#include <iostream>
#include <string>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/context.hpp"
#include "finflex/error.hpp"

namespace finflex::cli {
namespace {

// The device's extensions for sharing memory with graphics APIs, or "none".
std::string interop_extensions(const DeviceDescription& d) {
  std::string found;
  for (const char* name :
       {"cl_khr_gl_sharing", "cl_khr_gl_event", "cl_khr_egl_image", "cl_khr_egl_event",
        "cl_khr_external_memory", "cl_khr_external_memory_opaque_fd",
        "cl_khr_external_memory_dma_buf", "cl_khr_external_semaphore"}) {
    if (d.has_extension(name)) found += (found.empty() ? "" : " ") + std::string(name);
  }
  return found.empty() ? "none" : found;
}

int run_info() {
  try {
    const std::vector<DeviceDescription> devices = list_devices();
    if (devices.empty()) {
      return fail(
          "info",
          "no OpenCL platform or device found (is an ICD such as pocl-opencl-icd installed?)");
    }
    for (const DeviceDescription& d : devices) {
      std::cout << d.platform_index << ":" << d.device_index << (d.is_default ? " * " : "   ")
                << d.device_name << " [" << d.type << "] on " << d.platform_name << ", "
                << d.version << ", " << (d.global_memory_bytes >> 20) << " MiB, max allocation "
                << (d.max_allocation_bytes >> 20) << " MiB\n"
                << "      graphics interop: " << interop_extensions(d) << "\n";
    }
    std::cout << "* default device (select another with --device P:D or a name substring)\n";
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("info", error.what());
  }
}

}  // namespace

Command add_info_command(CLI::App& app) {
  app.add_subcommand("info", "List OpenCL platforms and devices, and the default one");
  return {[] {}, [] { return run_info(); }};
}

}  // namespace finflex::cli

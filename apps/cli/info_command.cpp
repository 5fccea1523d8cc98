// finflex info: the OpenCL platforms and devices, which one is the default, the
// extensions each offers for handing outputs to a renderer, and the hand-off paths it
// can take (docs/handoff.md).
#include <iostream>
#include <string>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/context.hpp"
#include "finflex/error.hpp"
#include "finflex/external_outputs.hpp"

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

// The hand-off paths the device can take, first to last, and why not external memory.
// (GL's side, importing the memory, is checked where a renderer exists: finflex swim.)
std::string hand_off_paths(const DeviceDescription& d) {
  std::string paths;
  std::string why_not;
  try {
    const Context context(std::to_string(d.platform_index) + ":" + std::to_string(d.device_index));
    const ExternalChoice choice = choose_external_device(context);
    if (choice.device) {
      const bool semaphores = choice.import == ExternalImport::kImported &&
                              choice.device->exports_semaphores() &&
                              d.has_extension("cl_khr_external_semaphore_opaque_fd");
      paths = std::string("external-memory (Vulkan ") + choice.device->name() + ", " +
              to_string(choice.import) + (semaphores ? ", semaphores" : ", host waits") + "), ";
    } else {
      why_not = "; no external memory: " + choice.why_not;
    }
  } catch (const std::exception& e) {
    why_not = std::string("; no external memory: ") + e.what();
  }
  if (d.has_extension("cl_khr_gl_sharing")) paths += "shared, ";
  return paths + "copy" + why_not;
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
                << "      graphics interop: " << interop_extensions(d) << "\n"
                << "      hand-off paths: " << hand_off_paths(d) << "\n";
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

// finflex info: the OpenCL platforms and devices, and which one is the default.
#include <iostream>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/context.hpp"
#include "finflex/error.hpp"

namespace finflex::cli {
namespace {

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
                << (d.max_allocation_bytes >> 20) << " MiB\n";
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

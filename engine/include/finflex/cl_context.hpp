// OpenCL plumbing: picks a platform and device, owns the context and an in-order
// profiling queue, and caches compiled programs by build options.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

namespace finflex {

struct DeviceDescription {
  std::size_t platform_index = 0;
  std::size_t device_index = 0;
  std::string platform_name;
  std::string device_name;
  std::string type;  // "GPU", "CPU", "accelerator" or "other"
  std::string version;
  std::size_t global_memory_bytes = 0;
  std::size_t max_allocation_bytes = 0;
  bool is_default = false;
};

// Every OpenCL device of every platform. The default is the first GPU found, else the
// first CPU device (PoCL), else the first device. Empty when no platform exists.
std::vector<DeviceDescription> list_devices();

// The source of one OpenCL program: embedded kernel files and generated text before them.
struct ProgramSource {
  std::vector<std::string> files;
  std::string generated;

  // bend.cl, planes.cl, deform_batch.cl, bandwidth.cl: the single-bend batch kernels.
  static ProgramSource bend_batch();
};

class Context {
 public:
  // `device` selects the device: empty for the default, "P:D" for platform P device D
  // (indices as list_devices() gives them), or a case-insensitive substring of the
  // device or platform name ("pocl", "H100"). The first match wins. Throws kDevice
  // naming the value when nothing matches or no OpenCL platform exists.
  explicit Context(const std::string& device = "");
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DeviceDescription& description() const { return description_; }
  const cl::Device& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // A program made of embedded kernel files (kernels/*.cl, by file name, in order),
  // after `generated` source text (e.g. a rig's dispatch macros), built once per
  // (files, options, generated) and cached. Build failures throw kOpenCL with the log.
  const cl::Program& program(const ProgramSource& source, const std::string& options);
  cl::Kernel kernel(const std::string& name, const ProgramSource& source,
                    const std::string& options);

 private:
  DeviceDescription description_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::mutex cache_mutex_;
  std::map<std::string, cl::Program> programs_;
};

// Throws finflex::Error (kOpenCL) "what: CL_... (code)" when status != CL_SUCCESS.
void check_cl(cl_int status, const char* what);

}  // namespace finflex

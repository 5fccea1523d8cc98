// OpenCL plumbing: picks a platform and device, owns the context and an in-order
// profiling queue, and caches compiled programs by build options.
//
// Thread-safety: a Context may be shared by any number of threads (deformers on
// several threads, program builds): the program cache is guarded by a lock, and the
// queue is used only through OpenCL calls, which are thread-safe. Every thread's
// commands go to the one in-order queue. Construction and destruction are not
// concurrent with any use.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/export.hpp"

namespace finflex {
namespace detail {
struct GateState;  // finflex/frame_gate.hpp
}

struct DeviceDescription {
  std::size_t platform_index = 0;
  std::size_t device_index = 0;
  std::string platform_name;
  std::string device_name;
  std::string type;  // "GPU", "CPU", "accelerator" or "other"
  std::string version;
  std::size_t global_memory_bytes = 0;
  std::size_t max_allocation_bytes = 0;
  std::string extensions;  // CL_DEVICE_EXTENSIONS, separated by spaces
  // Floats in the device's native vector (CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT): e.g. 16
  // on a CPU with AVX-512, 8 with AVX2.
  std::size_t native_float_vector_width = 1;
  // CL_DEVICE_GLOBAL_MEM_CACHE_SIZE: on CPUs, PoCL reports the last-level cache (in a
  // virtual machine, whatever the hypervisor says it is).
  std::size_t global_memory_cache_bytes = 0;
  // CL_DEVICE_MAX_COMPUTE_UNITS: on CPUs, the threads PoCL runs work-groups on.
  std::size_t compute_units = 1;
  bool is_default = false;

  bool is_gpu() const { return type == "GPU"; }
  // Whether `name` (e.g. "cl_khr_gl_sharing") is one of the device's extensions.
  bool has_extension(const std::string& name) const {
    const std::string padded = " " + extensions + " ";
    return padded.find(" " + name + " ") != std::string::npos;
  }
};

// Every OpenCL device of every platform. The default is the first GPU found, else the
// first CPU device (PoCL), else the first device. Empty when no platform exists.
FINFLEX_API std::vector<DeviceDescription> list_devices();

// The source of one OpenCL program: `generated` text (e.g. a rig's dispatch macros),
// then the library's embedded kernel files (paths under kernels/, e.g.
// "common/vec3.cl"), then `appended` text (kernels of the caller's own that use the
// library's functions).
struct ProgramSource {
  std::vector<std::string> files;
  std::string generated;
  std::string appended;
};

// The library's shared kernel files, in build order: lanes (the slots of a work-item)
// and vectors, the secant surface's (7) and (8), the planes (one lane, then more than
// one), the outputs' store epilogue (one lane, then more than one), stage frames, world
// placement.
FINFLEX_API const std::vector<std::string>& common_kernel_files();

class FINFLEX_API Context {
 public:
  // `device` selects the device: empty for the default, "P:D" for platform P device D
  // (indices as list_devices() gives them), or a case-insensitive substring of the
  // device or platform name ("pocl", "H100"). The first match wins. Throws kDevice
  // naming the value when nothing matches or no OpenCL platform exists.
  explicit Context(const std::string& device = "");
  // The same with context properties after CL_CONTEXT_PLATFORM (pairs, without the
  // closing 0), e.g. an OpenGL context to share buffers with (finflex/gl_outputs.hpp):
  // kOpenCL when the platform refuses them.
  Context(const std::string& device, const std::vector<cl_context_properties>& extra_properties);
  // Waits for the work on its queues, so that none is still running when the OpenCL
  // implementation shuts down with the process (PoCL compiles a kernel on its first
  // launch, in a thread of its own); opens every FrameGate of the context still closed
  // first, which nothing could open after it.
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DeviceDescription& description() const { return description_; }
  const cl::Device& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  // The extra context properties it was made with (pairs; empty for none).
  const std::vector<cl_context_properties>& extra_properties() const { return extra_properties_; }
  cl::CommandQueue& queue() { return queue_; }
  // A second queue of the device for blocking maps of staging memory, which return at
  // once there: the frames' queue may hold work behind a closed FrameGate.
  cl::CommandQueue& map_queue() { return map_queue_; }

  // The program of `source`, built once per (source, options) and cached. Every build
  // gets -cl-std=CL1.2 and FF_GPU (1 on GPUs: kernels pick the instructions that are
  // fast on the device's kind). Build failures throw kOpenCL with the log; an unknown
  // kernel file throws kOpenCL naming it.
  const cl::Program& program(const ProgramSource& source, const std::string& options);
  cl::Kernel kernel(const std::string& name, const ProgramSource& source,
                    const std::string& options);

 private:
  friend class FrameGate;
  // A FrameGate's user event, to be opened by ~Context if it is still closed then.
  void track_gate(const std::shared_ptr<detail::GateState>& gate);

  DeviceDescription description_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  cl::CommandQueue map_queue_;
  std::vector<cl_context_properties> extra_properties_;
  std::mutex cache_mutex_;
  std::map<std::string, cl::Program> programs_;
  std::mutex gates_mutex_;
  std::vector<std::shared_ptr<detail::GateState>> gates_;  // the gates not yet seen open
};

// Throws finflex::Error (kOpenCL) "what: CL_... (code)" when status != CL_SUCCESS.
FINFLEX_API void check_cl(cl_int status, const char* what);

}  // namespace finflex

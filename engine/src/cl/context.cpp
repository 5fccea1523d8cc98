#include "finflex/context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "cl/device_profile.hpp"
#include "cl/kernel_sources.hpp"
#include "finflex/error.hpp"
#include "finflex/frame_gate.hpp"

namespace finflex {
namespace {

const char* cl_status_name(cl_int status) {
  switch (status) {
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE:
      return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_MEM_OBJECT:
      return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_ARG_VALUE:
      return "CL_INVALID_ARG_VALUE";
    case CL_INVALID_ARG_SIZE:
      return "CL_INVALID_ARG_SIZE";
    case CL_PLATFORM_NOT_FOUND_KHR:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "CL error";
  }
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string device_type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

struct FoundDevice {
  DeviceDescription description;
  cl::Device device;
};

std::vector<FoundDevice> enumerate_devices() {
  std::vector<cl::Platform> platforms;
  if (cl::Platform::get(&platforms) != CL_SUCCESS) return {};
  std::vector<FoundDevice> found;
  for (std::size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    if (platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices) != CL_SUCCESS) continue;
    for (std::size_t d = 0; d < devices.size(); ++d) {
      FoundDevice f;
      f.device = devices[d];
      DeviceDescription& desc = f.description;
      desc.platform_index = p;
      desc.device_index = d;
      desc.platform_name = platforms[p].getInfo<CL_PLATFORM_NAME>();
      desc.device_name = devices[d].getInfo<CL_DEVICE_NAME>();
      desc.type = device_type_name(devices[d].getInfo<CL_DEVICE_TYPE>());
      desc.version = devices[d].getInfo<CL_DEVICE_VERSION>();
      desc.global_memory_bytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      desc.max_allocation_bytes = devices[d].getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      desc.extensions = devices[d].getInfo<CL_DEVICE_EXTENSIONS>();
      desc.native_float_vector_width = devices[d].getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
      desc.global_memory_cache_bytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_CACHE_SIZE>();
      desc.compute_units = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      found.push_back(f);
    }
  }
  auto first_of = [&](const std::string& type) {
    return std::find_if(found.begin(), found.end(),
                        [&](const FoundDevice& f) { return f.description.type == type; });
  };
  auto chosen = first_of("GPU");
  if (chosen == found.end()) chosen = first_of("CPU");
  if (chosen == found.end()) chosen = found.begin();
  if (chosen != found.end()) chosen->description.is_default = true;
  return found;
}

bool matches(const DeviceDescription& d, const std::string& selector) {
  if (selector.empty()) return d.is_default;
  if (selector == std::to_string(d.platform_index) + ":" + std::to_string(d.device_index)) {
    return true;
  }
  const std::string needle = lower(selector);
  return lower(d.device_name).find(needle) != std::string::npos ||
         lower(d.platform_name).find(needle) != std::string::npos;
}

}  // namespace

void check_cl(cl_int status, const char* what) {
  if (status == CL_SUCCESS) return;
  throw Error(ErrorCode::kOpenCL, what,
              std::string(what) + " failed: " + cl_status_name(status) + " (" +
                  std::to_string(status) + ")");
}

std::vector<DeviceDescription> list_devices() {
  std::vector<DeviceDescription> out;
  for (const FoundDevice& f : enumerate_devices()) out.push_back(f.description);
  return out;
}

Context::Context(const std::string& device) : Context(device, {}) {}

Context::Context(const std::string& device,
                 const std::vector<cl_context_properties>& extra_properties)
    : extra_properties_(extra_properties) {
  const std::vector<FoundDevice> found = enumerate_devices();
  if (found.empty()) {
    throw Error(
        ErrorCode::kDevice, "device",
        "no OpenCL platform or device found (is an ICD such as pocl-opencl-icd installed?)");
  }
  auto chosen = std::find_if(found.begin(), found.end(),
                             [&](const FoundDevice& f) { return matches(f.description, device); });
  if (chosen == found.end()) {
    std::string names;
    for (const FoundDevice& f : found) {
      names += (names.empty() ? "" : ", ") + std::to_string(f.description.platform_index) + ":" +
               std::to_string(f.description.device_index) + " '" + f.description.device_name + "'";
    }
    throw Error(ErrorCode::kDevice, "device",
                "device '" + device + "' matches no OpenCL device (available: " + names + ")");
  }
  description_ = chosen->description;
  device_ = chosen->device;
  cl_int status = CL_SUCCESS;
  if (extra_properties.empty()) {
    context_ = cl::Context(device_, nullptr, nullptr, nullptr, &status);
  } else {
    cl_platform_id platform = nullptr;
    check_cl(device_.getInfo(CL_DEVICE_PLATFORM, &platform), "clGetDeviceInfo");
    std::vector<cl_context_properties> properties = {
        CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(platform)};
    properties.insert(properties.end(), extra_properties.begin(), extra_properties.end());
    properties.push_back(0);
    context_ = cl::Context(device_, properties.data(), nullptr, nullptr, &status);
  }
  check_cl(status, "clCreateContext");
  queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE, &status);
  check_cl(status, "clCreateCommandQueue");
  map_queue_ = cl::CommandQueue(context_, device_, 0, &status);
  check_cl(status, "clCreateCommandQueue (maps)");
}

Context::~Context() {
  // Nothing may throw here: failures are ignored.
  for (const std::shared_ptr<detail::GateState>& gate : gates_) {
    if (!gate->opened.exchange(true)) gate->event.setStatus(CL_COMPLETE);
  }
  queue_.finish();
  map_queue_.finish();
}

void Context::track_gate(const std::shared_ptr<detail::GateState>& gate) {
  std::lock_guard<std::mutex> lock(gates_mutex_);
  // The opened gates are dropped, so the list holds the few of the frames in flight.
  gates_.erase(
      std::remove_if(gates_.begin(), gates_.end(),
                     [](const std::shared_ptr<detail::GateState>& g) { return g->opened.load(); }),
      gates_.end());
  gates_.push_back(gate);
}

const std::vector<std::string>& common_kernel_files() {
  static const std::vector<std::string> files = {
      "common/lanes.cl",   "common/vec3.cl",      "common/trig.cl",          "common/scan.cl",
      "common/secant.cl",  "common/planes.cl",    "common/instance_list.cl", "cpu/lane_planes.cl",
      "common/outputs.cl", "cpu/lane_outputs.cl", "common/stage_frame.cl",   "common/placement.cl"};
  return files;
}

const cl::Program& Context::program(const ProgramSource& source, const std::string& options) {
  std::string key = options + '\n' + source.generated + '\n' + source.appended;
  for (const std::string& file : source.files) key += '\n' + file;
  std::lock_guard<std::mutex> lock(cache_mutex_);
  auto cached = programs_.find(key);
  if (cached != programs_.end()) return cached->second;

  cl::Program::Sources sources;
  if (!source.generated.empty()) sources.push_back(source.generated);
  for (const std::string& file : source.files) {
    const auto& embedded = detail::kernel_sources();
    auto found = std::find_if(embedded.begin(), embedded.end(),
                              [&](const detail::KernelSource& k) { return k.file_name == file; });
    if (found == embedded.end()) {
      throw Error(ErrorCode::kOpenCL, "kernels", "no embedded kernel file '" + file + "'");
    }
    sources.push_back(found->text);
  }
  if (!source.appended.empty()) sources.push_back(source.appended);
  cl_int status = CL_SUCCESS;
  // FF_GPU: the kernels pick the instructions that are fast on the device's kind
  // (kernels/common/planes.cl's half conversion).
  // FF_NATIVE_TRIG: the hardware's sine and cosine (detail::device_native_trig).
  const std::string device_options =
      std::string(description_.is_gpu() ? "-DFF_GPU=1 " : "-DFF_GPU=0 ") +
      (detail::device_native_trig(description_) ? "-DFF_NATIVE_TRIG=1 " : "-DFF_NATIVE_TRIG=0 ");
  const std::string full_options = "-cl-std=CL1.2 " + device_options + options;
  // A compiler's diagnostics stay out of the user's terminal: every build passes -w (no
  // warnings; PoCL's clang otherwise prints "N warnings generated." on the process's
  // stderr, the warnings themselves going to the build log), and a failed build's log
  // (its errors) is the Error's message. PoCL's clang still prints "N errors generated."
  // when a build fails (its option list admits no -fno-caret-diagnostics). With
  // FINFLEX_KERNEL_WARNINGS=1 in the environment (tests/test_kernel_warnings.cpp,
  // kernel work) each program is first built with -Werror, warnings shown: any warning
  // fails the build and throws with the log, as does a log that still names one; then
  // it is built as always (the kernels run are those of a plain build). NVIDIA's
  // compiler (OpenCL C 1.2 only) takes -w and -Werror (OpenCL 1.2, 5.6.4.4) and writes
  // its diagnostics to the build log only; the kernels must build there without
  // warnings too: run that test on an NVIDIA device (scripts/device/run.sh gpu_checks).
  auto build = [&](const std::string& warnings) {
    const std::string built_with = full_options + " " + warnings;
    cl::Program built(context_, sources, &status);
    check_cl(status, "clCreateProgramWithSource");
    status = built.build(std::vector<cl::Device>{device_}, built_with.c_str());
    std::string log;
    built.getBuildInfo(device_, CL_PROGRAM_BUILD_LOG, &log);
    const bool warned = warnings == "-Werror" && log.find("warning") != std::string::npos;
    if (status != CL_SUCCESS || warned) {
      throw Error(ErrorCode::kOpenCL, "kernels",
                  "building the kernels with '" + built_with + "' " +
                      (status != CL_SUCCESS ? "failed" : "warned") + " on '" +
                      description_.device_name + "': " + log);
    }
    return built;
  };
  const char* warnings_fail = std::getenv("FINFLEX_KERNEL_WARNINGS");
  if (warnings_fail != nullptr && *warnings_fail != '\0' && std::string(warnings_fail) != "0") {
    build("-Werror");
  }
  return programs_.emplace(key, build("-w")).first->second;
}

cl::Kernel Context::kernel(const std::string& name, const ProgramSource& source,
                           const std::string& options) {
  cl_int status = CL_SUCCESS;
  cl::Kernel kernel(program(source, options), name.c_str(), &status);
  check_cl(status, ("clCreateKernel " + name).c_str());
  return kernel;
}

}  // namespace finflex

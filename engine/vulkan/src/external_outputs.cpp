#include "finflex/external_outputs.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "cl_external_functions.hpp"
#include "finflex/error.hpp"

namespace finflex {
namespace {

constexpr const char* kMemoryExtension = "cl_khr_external_memory_opaque_fd";
constexpr const char* kSemaphoreExtension = "cl_khr_external_semaphore_opaque_fd";

cl_platform_id platform_of(const Context& context) {
  cl_platform_id platform = nullptr;
  check_cl(context.device().getInfo(CL_DEVICE_PLATFORM, &platform), "clGetDeviceInfo");
  return platform;
}

// Bytes a buffer needs for `attribute`: what the engine checks, and every plane whole.
std::size_t attribute_bytes(const AttributeLayout& attribute, std::size_t instances,
                            std::size_t vertices) {
  return std::max(OutputLayout::required_bytes(attribute, instances, vertices),
                  attribute.offset + instances * attribute.instance_stride);
}

std::string no_uuid(const Context& context) {
  return "'" + context.description().device_name +
         "' has no cl_khr_device_uuid to match a Vulkan device by";
}

}  // namespace

const char* to_string(ExternalImport import) {
  return import == ExternalImport::kImported ? "imported" : "host-mapped";
}

std::optional<vulkan::Uuid> opencl_device_uuid(const Context& context) {
  if (!context.description().has_extension("cl_khr_device_uuid")) return std::nullopt;
  vulkan::Uuid uuid{};
  check_cl(
      clGetDeviceInfo(context.device()(), CL_DEVICE_UUID_KHR, uuid.size(), uuid.data(), nullptr),
      "clGetDeviceInfo(CL_DEVICE_UUID_KHR)");
  return uuid;
}

std::string why_not_external(const Context& context, const vulkan::Device& device,
                             ExternalImport* import) {
  const DeviceDescription& cl = context.description();
  const std::string name = "'" + cl.device_name + "'";
  if (cl.has_extension(kMemoryExtension)) {
    const std::optional<vulkan::Uuid> uuid = opencl_device_uuid(context);
    if (!uuid) return no_uuid(context);
    if (*uuid != device.uuid()) {
      return name + "'s UUID " + vulkan::to_string(*uuid) + " is not the Vulkan device's (" +
             device.name() + ", " + vulkan::to_string(device.uuid()) + ")";
    }
    if (!detail::load_cl_external_functions(platform_of(context)).has_memory()) {
      return name +
             "'s platform or the OpenCL loader lacks clCreateBufferWithProperties or "
             "clEnqueueAcquireExternalMemObjectsKHR";
    }
    if (import) *import = ExternalImport::kImported;
    return "";
  }
  if (cl.type == "CPU" && device.is_cpu()) {
    if (import) *import = ExternalImport::kHostMapped;
    return "";
  }
  return name + " has no " + kMemoryExtension + (cl.type == "CPU" ? "" : " and is not a CPU") +
         (device.is_cpu() ? "" : " (the Vulkan device '" + device.name() + "' is no CPU either)");
}

ExternalChoice choose_external_device(const Context& context) {
  ExternalChoice out;
  const std::optional<vulkan::Uuid> uuid = opencl_device_uuid(context);
  if (!uuid && context.description().type != "CPU") {
    out.why_not = no_uuid(context);
    return out;
  }
  try {
    out.device = vulkan::Device::open(uuid);
  } catch (const Error& e) {
    out.why_not = e.what();
    return out;
  }
  out.why_not = why_not_external(context, *out.device, &out.import);
  if (!out.why_not.empty()) out.device.reset();
  return out;
}

// OpenCL's entry points, and its handles of the two semaphores (null without them).
struct ExternalOutputs::ClImports {
  detail::ClExternalFunctions f;
  cl_semaphore_khr kernels_done = nullptr;
  cl_semaphore_khr consumer_done = nullptr;
  ~ClImports() {
    if (kernels_done) f.release_semaphore(kernels_done);
    if (consumer_done) f.release_semaphore(consumer_done);
  }
};

namespace {

cl_semaphore_khr import_semaphore(const detail::ClExternalFunctions& f, const Context& context,
                                  const vulkan::ExternalSemaphore& semaphore) {
  const int fd = semaphore.export_fd();
  // No device list: the context has one device (the list's enum differs between
  // revisions of the extension's headers, 0x2051 and 0x2053).
  const cl_semaphore_properties_khr properties[] = {
      CL_SEMAPHORE_TYPE_KHR, CL_SEMAPHORE_TYPE_BINARY_KHR, CL_SEMAPHORE_HANDLE_OPAQUE_FD_KHR,
      static_cast<cl_semaphore_properties_khr>(fd), 0};
  cl_int status = CL_SUCCESS;
  cl_semaphore_khr out = f.create_semaphore(context.context()(), properties, &status);
  if (status != CL_SUCCESS) close(fd);
  check_cl(status, "clCreateSemaphoreWithPropertiesKHR (opaque fd)");
  return out;
}

}  // namespace

ExternalOutputs::ExternalOutputs(ClDeformer& deformer, std::size_t instances,
                                 const OutputLayout& layout, const vulkan::Device& device,
                                 std::array<std::size_t, 4> buffer_of, std::size_t tail_bytes,
                                 std::size_t side_bytes)
    : deformer_(deformer), layout_(layout), side_bytes_(side_bytes) {
  Context& context = deformer.context();
  const std::string why = why_not_external(context, device, &import_);
  if (!why.empty()) throw Error(ErrorCode::kDevice, "vulkan", "external memory: " + why);

  // The distinct buffers, in increasing order of buffer_of, and their sizes.
  const std::array<const AttributeLayout*, 4> written = layout.written();
  std::vector<std::size_t> ids;
  for (std::size_t k = 0; k < 4; ++k) {
    if (written[k]) ids.push_back(buffer_of[k]);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  data_bytes_.assign(ids.size(), 0);
  const std::size_t vertices = deformer.output_vertices(layout.order);
  for (std::size_t k = 0; k < 4; ++k) {
    if (!written[k]) continue;
    buffer_index_[k] = static_cast<std::size_t>(
        std::lower_bound(ids.begin(), ids.end(), buffer_of[k]) - ids.begin());
    data_bytes_[buffer_index_[k]] =
        std::max(data_bytes_[buffer_index_[k]], attribute_bytes(*written[k], instances, vertices));
  }
  constexpr std::size_t kSideAlignment = 256;  // any importer's offset alignment
  side_offset_ = (data_bytes_[0] + kSideAlignment - 1) / kSideAlignment * kSideAlignment;
  for (std::size_t b = 0; b < data_bytes_.size(); ++b) {
    const std::size_t used =
        b == 0 && side_bytes_ > 0 ? side_offset_ + side_bytes_ : data_bytes_[b];
    buffers_.push_back(std::make_unique<vulkan::ExternalBuffer>(device, used + tail_bytes));
  }

  if (import_ == ExternalImport::kHostMapped) {
    semaphores_why_not_ = "a CPU device writes the memory through its host mapping";
    HostOutputs host;
    void** pointers[4] = {&host.positions, &host.normals, &host.tangents, &host.previous_positions};
    std::size_t* sizes[4] = {&host.positions_bytes, &host.normals_bytes, &host.tangents_bytes,
                             &host.previous_positions_bytes};
    for (std::size_t k = 0; k < 4; ++k) {
      if (!written[k]) continue;
      const vulkan::ExternalBuffer& buffer = *buffers_[buffer_index_[k]];
      if (!buffer.host_visible()) {
        throw Error(ErrorCode::kDevice, "vulkan",
                    "external memory: '" + device.name() + "' gave memory the host cannot map");
      }
      *pointers[k] = buffer.mapped();
      *sizes[k] = data_bytes_[buffer_index_[k]];
    }
    batch_ = deformer.bind_host(instances, layout, host);
    return;
  }

  // kImported: each buffer's memory as an OpenCL buffer, then semaphores where both
  // sides have them.
  cl_ = std::make_unique<ClImports>();
  cl_->f = detail::load_cl_external_functions(platform_of(context));
  const detail::ClExternalFunctions& f = cl_->f;
  for (std::size_t b = 0; b < buffers_.size(); ++b) {
    const int fd = buffers_[b]->export_fd();
    const cl_ulong properties[] = {CL_EXTERNAL_MEMORY_HANDLE_OPAQUE_FD_KHR,
                                   static_cast<cl_ulong>(fd),
                                   CL_DEVICE_HANDLE_LIST_KHR,
                                   reinterpret_cast<cl_ulong>(context.device()()),
                                   CL_DEVICE_HANDLE_LIST_END_KHR,
                                   0};
    cl_int status = CL_SUCCESS;
    const std::size_t used =
        b == 0 && side_bytes_ > 0 ? side_offset_ + side_bytes_ : data_bytes_[b];
    cl_mem memory = f.create_buffer_with_properties(context.context()(), properties,
                                                    CL_MEM_READ_WRITE, used, nullptr, &status);
    if (status != CL_SUCCESS) close(fd);  // on success the implementation owns it
    check_cl(status, "clCreateBufferWithProperties (external memory, opaque fd)");
    imported_.emplace_back(memory);  // takes the reference
  }
  OutputBuffers buffers;
  cl::Buffer* slots[4] = {&buffers.positions, &buffers.normals, &buffers.tangents,
                          &buffers.previous_positions};
  for (std::size_t k = 0; k < 4; ++k) {
    if (written[k]) *slots[k] = imported_[buffer_index_[k]];
  }
  batch_ = deformer.bind(instances, layout, buffers);
  // OpenCL acquires the imported memory once, for the outputs' life (released in the
  // destructor): the frames are ordered by the semaphores or by the host, and
  // NVIDIA's acquire blocks the host until its wait list is complete, which behind a
  // FrameGate never happens before the frame is enqueued.
  acquire_or_release(true);

  if (!device.exports_semaphores()) {
    semaphores_why_not_ = "'" + device.name() + "' exports no semaphores as opaque fds";
  } else if (!context.description().has_extension(kSemaphoreExtension)) {
    semaphores_why_not_ =
        "'" + context.description().device_name + "' has no " + kSemaphoreExtension;
  } else if (!f.has_semaphores()) {
    semaphores_why_not_ = "the OpenCL platform lacks clCreateSemaphoreWithPropertiesKHR";
  } else {
    try {
      kernels_done_ = std::make_unique<vulkan::ExternalSemaphore>(device);
      consumer_done_ = std::make_unique<vulkan::ExternalSemaphore>(device);
      cl_->kernels_done = import_semaphore(f, context, *kernels_done_);
      cl_->consumer_done = import_semaphore(f, context, *consumer_done_);
    } catch (const Error& e) {
      // Without them the frames are ordered on the host: slower, as correct.
      semaphores_why_not_ = e.what();
      if (cl_->kernels_done) f.release_semaphore(cl_->kernels_done);
      cl_->kernels_done = nullptr;
      kernels_done_.reset();
      consumer_done_.reset();
    }
  }
}

void ExternalOutputs::acquire_or_release(bool acquire) {
  std::vector<cl_mem> memory;
  for (const cl::Buffer& m : imported_) memory.push_back(m());
  cl::CommandQueue& queue = deformer_.context().queue();
  const auto call = acquire ? cl_->f.acquire : cl_->f.release;
  check_cl(
      call(queue(), static_cast<cl_uint>(memory.size()), memory.data(), 0, nullptr, nullptr),
      acquire ? "clEnqueueAcquireExternalMemObjectsKHR" : "clEnqueueReleaseExternalMemObjectsKHR");
  check_cl(queue.finish(), "clFinish");
}

ExternalOutputs::~ExternalOutputs() {
  // The device may still use the memory: release it and let the queue drain before
  // Vulkan frees it.
  try {
    if (import_ == ExternalImport::kImported && cl_) acquire_or_release(false);
    deformer_.context().queue().finish();
  } catch (...) {
  }
}

void ExternalOutputs::enqueue_copies(const std::vector<SideCopy>& copies) {
  cl::CommandQueue& queue = deformer_.context().queue();
  for (const SideCopy& copy : copies) {
    if (copy.bytes == 0) continue;
    const std::size_t at = side_offset_ + copy.offset;
    if (import_ == ExternalImport::kHostMapped) {  // the region is host memory
      auto* region = static_cast<unsigned char*>(buffers_[0]->mapped()) + at;
      check_cl(
          queue.enqueueReadBuffer(*copy.source, CL_FALSE, copy.source_offset, copy.bytes, region),
          "clEnqueueReadBuffer (side copy)");
    } else {
      check_cl(
          queue.enqueueCopyBuffer(*copy.source, imported_[0], copy.source_offset, at, copy.bytes),
          "clEnqueueCopyBuffer (side copy)");
    }
  }
}

cl::Event ExternalOutputs::enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events,
                                   const std::vector<SideCopy>& copies) {
  for (std::size_t i = 0; i < copies.size(); ++i) {
    const SideCopy& copy = copies[i];
    const std::string field = "copies[" + std::to_string(i) + "]";
    if (copy.source == nullptr || (*copy.source)() == nullptr) {
      throw Error(ErrorCode::kInvalidArgument, field, field + ": no source buffer");
    }
    if (copy.offset > side_bytes_ || copy.bytes > side_bytes_ - copy.offset) {
      throw Error(ErrorCode::kInvalidArgument, field,
                  field + ": " + std::to_string(copy.bytes) + " bytes at " +
                      std::to_string(copy.offset) + " pass the side region's " +
                      std::to_string(side_bytes_));
    }
  }
  if (job.outputs != &batch_) {
    throw Error(ErrorCode::kInvalidArgument, "job.outputs",
                "job.outputs: an ExternalOutputs frame writes its own batch() (set job.outputs "
                "to it)");
  }
  if (reading_) {
    throw Error(ErrorCode::kInvalidArgument, "enqueue",
                "enqueue: the batch is being read (begin_reading without end_reading)");
  }
  if (import_ == ExternalImport::kHostMapped) {
    enqueue_copies(copies);  // the in-order queue: done before the kernels' event
    last_ = deformer_.enqueue(job, kernel_events);
    return last_;
  }
  cl::CommandQueue& queue = deformer_.context().queue();
  const detail::ClExternalFunctions& f = cl_->f;
  if (device_ordered() && consumer_pending_) {
    check_cl(f.wait_semaphores(queue(), 1, &cl_->consumer_done, nullptr, 0, nullptr, nullptr),
             "clEnqueueWaitSemaphoresKHR");
    consumer_pending_ = false;
  }
  enqueue_copies(copies);
  last_ = deformer_.enqueue(job, kernel_events);
  if (device_ordered()) {
    // No wait list: the in-order queue puts the signal after the kernels, and NVIDIA's
    // semaphore and acquire calls wait on the host for the events they are given.
    cl_event signalled = nullptr;
    check_cl(f.signal_semaphores(queue(), 1, &cl_->kernels_done, nullptr, 0, nullptr, &signalled),
             "clEnqueueSignalSemaphoresKHR");
    last_ = cl::Event(signalled);
  }
  check_cl(queue.flush(), "clFlush");  // the consumer's wait needs the signal submitted
  return last_;
}

void ExternalOutputs::wait_for_frame() {
  if (last_() == nullptr) return;  // no frame yet
  check_cl(last_.wait(), "clWaitForEvents");
  if (import_ == ExternalImport::kHostMapped && !batch_.host_mapped) deformer_.map_host(batch_);
}

void ExternalOutputs::begin_reading() {
  if (reading_) return;
  wait_for_frame();  // OpenCL holds imported memory throughout: nothing to acquire
  reading_ = true;
}

void ExternalOutputs::end_reading() { reading_ = false; }

}  // namespace finflex

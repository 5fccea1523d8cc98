// The external-memory hand-off (library FinFlex::vulkan, docs/handoff.md "Zero-copy
// hand-off"): a batch's outputs in Vulkan memory that the kernels write and any other
// API reads in place, with no byte crossing the host.
//
//   ExternalChoice choice = choose_external_device(context);   // matched by UUID
//   if (choice.device) {
//     ExternalOutputs outputs(deformer, 1000, layout, *choice.device);
//     int fd = outputs.buffer(0).export_fd();        // a fresh fd for each importer
//     ... glImportMemoryFdEXT(memory, outputs.buffer(0).memory_bytes(), ..., fd) ...
//     job.outputs = &outputs.batch();
//     each frame: cl::Event ready = outputs.enqueue(job);
//                 the consumer waits for kernels_done() (or `ready`), reads, signals
//                 consumer_done() and calls outputs.consumer_signalled();
//   } else  ...  choice.why_not says why, and the caller takes the next path.
//
// Two imports, chosen from the OpenCL device:
//  - kImported: cl_khr_external_memory_opaque_fd (NVIDIA): each buffer's fd imported
//    with clCreateBufferWithProperties and acquired by OpenCL once, for the outputs'
//    life.
//    Where both OpenCL (cl_khr_external_semaphore_opaque_fd) and Vulkan export binary
//    semaphores, the frame orders itself on the device: OpenCL waits for
//    consumer_done() before the next frame's kernels (once the consumer has signalled
//    it) and signals kernels_done() after them; no host wait.
//  - kHostMapped: an OpenCL CPU device (PoCL) beside a Vulkan CPU device (lavapipe),
//    whose memory is host memory: the kernels write the mapped memory
//    (ClDeformer::bind_host). No semaphores: wait_for_frame() blocks until the frame is
//    there, and the consumer is done with a frame before the next enqueue.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/cl_deformer.hpp"
#include "finflex/context.hpp"
#include "finflex/external_memory.hpp"
#include "finflex/output_layout.hpp"
#include "finflex/vulkan_device.hpp"

namespace finflex {

enum class ExternalImport { kImported, kHostMapped };
const char* to_string(ExternalImport import);  // "imported", "host-mapped"

// The OpenCL device's UUID (cl_khr_device_uuid), nullopt without the extension.
std::optional<vulkan::Uuid> opencl_device_uuid(const Context& context);

// Why `context`'s device cannot write `device`'s exported memory (empty: it can, and
// `import` says how).
std::string why_not_external(const Context& context, const vulkan::Device& device,
                             ExternalImport* import = nullptr);

// The Vulkan device for `context`'s OpenCL device: the one with its UUID, or for a CPU
// device without one the Vulkan CPU device; null with why_not when there is none or it
// cannot serve (no loader, no such device, an extension missing: each named).
struct ExternalChoice {
  std::unique_ptr<vulkan::Device> device;
  ExternalImport import = ExternalImport::kImported;
  std::string why_not;
};
ExternalChoice choose_external_device(const Context& context);

// A copy that each frame makes into the outputs' side region (ExternalOutputs'
// side_bytes): `bytes` of `source` from `source_offset` to `offset` in the region.
struct SideCopy {
  const cl::Buffer* source = nullptr;
  std::size_t source_offset = 0;
  std::size_t bytes = 0;
  std::size_t offset = 0;
};

class ExternalOutputs {
 public:
  // Buffers in `device`'s memory for `instances` instances in `layout`, one per
  // distinct value of `buffer_of` (the buffer of positions, normals, tangents and
  // previous positions: {0, 0, 0, 0} interleaves them all in one), each as large as
  // its attributes need (OutputLayout::required_bytes; every plane whole) plus
  // `tail_bytes` that importers may want beyond the data (Mesa's GL needs 64).
  // `side_bytes`: a side region of buffer 0 after its data, from side_offset()
  // (256-byte aligned), that each frame fills from other OpenCL buffers (enqueue's
  // copies) for the consumer to read beside the outputs, ordered as they are: e.g. a
  // level's indirect draw command and instance list (LevelChooser).
  // The layout is checked as ClDeformer::bind does. Errors: kDevice naming
  // why_not_external's reason; kOpenCL when an import fails.
  ExternalOutputs(ClDeformer& deformer, std::size_t instances, const OutputLayout& layout,
                  const vulkan::Device& device, std::array<std::size_t, 4> buffer_of = {0, 1, 2, 3},
                  std::size_t tail_bytes = 256, std::size_t side_bytes = 0);
  ~ExternalOutputs();
  ExternalOutputs(const ExternalOutputs&) = delete;
  ExternalOutputs& operator=(const ExternalOutputs&) = delete;

  ExternalImport import() const { return import_; }
  DeviceBatch& batch() { return batch_; }
  const OutputLayout& layout() const { return layout_; }

  // The buffers (index: a value of buffer_of, in increasing order) and which one holds
  // each attribute (positions, normals, tangents, previous positions; written ones).
  std::size_t buffer_count() const { return buffers_.size(); }
  const vulkan::ExternalBuffer& buffer(std::size_t k) const { return *buffers_.at(k); }
  std::size_t buffer_of(std::size_t attribute) const { return buffer_index_.at(attribute); }
  // The bytes of buffer k that hold data (without the side region and the tail).
  std::size_t data_bytes(std::size_t k) const { return data_bytes_.at(k); }
  // Buffer 0's side region: from side_offset(), side_bytes() long (0: none).
  std::size_t side_offset() const { return side_offset_; }
  std::size_t side_bytes() const { return side_bytes_; }

  // Whether the frame orders itself on the device through the two semaphores (else
  // both are null and the consumer waits on the host).
  bool device_ordered() const { return kernels_done_ != nullptr; }
  const vulkan::ExternalSemaphore* kernels_done() const { return kernels_done_.get(); }
  const vulkan::ExternalSemaphore* consumer_done() const { return consumer_done_.get(); }
  // Why the frame is not device-ordered (empty when it is).
  const std::string& semaphores_why_not() const { return semaphores_why_not_; }

  // Enqueues `copies` into the side region, then `job` (its outputs must be batch()),
  // as the import says; returns the event after which the frame is in the memory
  // (device-ordered: the semaphore's signal). `kernel_events` as ClDeformer::enqueue.
  // kInvalidArgument naming "copies[i]" (no source, or past the side region), nothing
  // enqueued.
  cl::Event enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events = nullptr,
                    const std::vector<SideCopy>& copies = {});
  // The consumer has signalled consumer_done() after its last read of the frame (and
  // flushed): the next enqueue waits for it on the device.
  void consumer_signalled() { consumer_pending_ = true; }
  // Blocks until the last enqueued frame is in the memory (kHostMapped: the batch is
  // mapped for the host; a CPU device wrote it there).
  void wait_for_frame();
  // Blocking OpenCL reads of batch() between frames (ClDeformer::read) go between these:
  // the last frame is waited for (kHostMapped: and mapped).
  void begin_reading();
  void end_reading();

 private:
  ClDeformer& deformer_;
  ExternalImport import_ = ExternalImport::kImported;
  OutputLayout layout_;
  std::vector<std::unique_ptr<vulkan::ExternalBuffer>> buffers_;
  std::array<std::size_t, 4> buffer_index_{};
  std::vector<std::size_t> data_bytes_;
  std::size_t side_offset_ = 0;
  std::size_t side_bytes_ = 0;
  std::vector<cl::Buffer> imported_;  // kImported: the buffers as OpenCL memory
  std::unique_ptr<vulkan::ExternalSemaphore> kernels_done_;
  std::unique_ptr<vulkan::ExternalSemaphore> consumer_done_;
  void acquire_or_release(bool acquire);  // kImported: blocking
  void enqueue_copies(const std::vector<SideCopy>& copies);
  struct ClImports;  // kImported: OpenCL's entry points and semaphores
  std::unique_ptr<ClImports> cl_;
  std::string semaphores_why_not_;
  bool consumer_pending_ = false;
  bool reading_ = false;
  DeviceBatch batch_;
  cl::Event last_;
};

}  // namespace finflex

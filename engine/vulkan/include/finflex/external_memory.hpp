// Exportable Vulkan memory and semaphores (library FinFlex::vulkan): what the
// external-memory hand-off shares between OpenCL, OpenGL and Vulkan.
//
// Each export_fd() is a fresh file descriptor that the caller owns until an importer
// takes it (clCreateBufferWithProperties, glImportMemoryFdEXT and vkAllocateMemory
// with VkImportMemoryFdInfoKHR each take ownership on success): one fd per importer,
// never one fd for two.
#pragma once

#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan_core.h>

#include "finflex/vulkan_device.hpp"

namespace finflex::vulkan {

// A buffer in its own (dedicated) allocation, exportable as an opaque fd; device-local
// where the device has such memory, and host-visible too where that memory is (a CPU
// device: then mapped() is the memory). Usage: storage, vertex, transfer source and
// destination.
class ExternalBuffer {
 public:
  // `bytes` > 0 (kInvalidArgument naming "bytes"). Errors: kDevice when the device
  // has no exportable memory type for the buffer.
  ExternalBuffer(const Device& device, std::size_t bytes);
  ~ExternalBuffer();
  ExternalBuffer(const ExternalBuffer&) = delete;
  ExternalBuffer& operator=(const ExternalBuffer&) = delete;

  VkBuffer buffer() const { return buffer_; }
  VkDeviceMemory memory() const { return memory_; }
  std::size_t bytes() const { return bytes_; }                // the buffer's
  std::size_t memory_bytes() const { return memory_bytes_; }  // the allocation's (>= bytes)
  // The allocation's memory type: an importer of the fd on the same physical device
  // allocates memory_bytes() of this type (opaque fds carry no type of their own).
  std::uint32_t memory_type() const { return memory_type_; }
  bool host_visible() const { return mapped_ != nullptr; }
  void* mapped() const { return mapped_; }  // host-visible memory, mapped whole; else null

  // A new fd of the memory (vkGetMemoryFdKHR), owned by the caller.
  int export_fd() const;

 private:
  const Device& device_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  std::size_t bytes_ = 0;
  std::size_t memory_bytes_ = 0;
  std::uint32_t memory_type_ = 0;
  void* mapped_ = nullptr;
};

// A binary semaphore exportable as an opaque fd (Device::exports_semaphores()).
class ExternalSemaphore {
 public:
  // Errors: kDevice when the device does not export semaphores.
  explicit ExternalSemaphore(const Device& device);
  ~ExternalSemaphore();
  ExternalSemaphore(const ExternalSemaphore&) = delete;
  ExternalSemaphore& operator=(const ExternalSemaphore&) = delete;

  VkSemaphore semaphore() const { return semaphore_; }
  // A new fd of the semaphore (vkGetSemaphoreFdKHR), owned by the caller.
  int export_fd() const;

 private:
  const Device& device_;
  VkSemaphore semaphore_ = VK_NULL_HANDLE;
};

}  // namespace finflex::vulkan

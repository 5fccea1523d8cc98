#include "finflex/external_memory.hpp"

#include <string>

#include <volk.h>

#include "finflex/error.hpp"

namespace finflex::vulkan {

ExternalBuffer::ExternalBuffer(const Device& device, std::size_t bytes)
    : device_(device), bytes_(bytes) {
  if (bytes == 0) throw Error(ErrorCode::kInvalidArgument, "bytes", "bytes: 0");
  const VkDevice vk = device.device();
  VkExternalMemoryBufferCreateInfo external{};
  external.sType = VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO;
  external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.pNext = &external;
  info.size = bytes;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check_vk(vkCreateBuffer(vk, &info, nullptr, &buffer_), "vkCreateBuffer");

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(vk, buffer_, &requirements);
  // Device-local first (a GPU's own memory); on a CPU device that memory is host
  // visible as well, and mapped below.
  std::optional<std::uint32_t> type =
      device.memory_type(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!type) type = device.memory_type(requirements.memoryTypeBits, 0);
  if (!type) {
    vkDestroyBuffer(vk, buffer_, nullptr);
    throw Error(ErrorCode::kDevice, "vulkan",
                "vulkan: '" + device.name() + "' has no memory type for an exportable buffer");
  }
  VkMemoryDedicatedAllocateInfo dedicated{};
  dedicated.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO;
  dedicated.buffer = buffer_;
  VkExportMemoryAllocateInfo export_info{};
  export_info.sType = VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO;
  export_info.pNext = &dedicated;
  export_info.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.pNext = &export_info;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = *type;
  const VkResult allocated = vkAllocateMemory(vk, &allocate, nullptr, &memory_);
  if (allocated != VK_SUCCESS) {
    vkDestroyBuffer(vk, buffer_, nullptr);
    check_vk(allocated, "vkAllocateMemory");
  }
  memory_bytes_ = requirements.size;
  memory_type_ = *type;
  check_vk(vkBindBufferMemory(vk, buffer_, memory_, 0), "vkBindBufferMemory");
  if (device.memory_type(1u << *type, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                          VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) {
    check_vk(vkMapMemory(vk, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  }
}

ExternalBuffer::~ExternalBuffer() {
  const VkDevice vk = device_.device();
  if (mapped_ != nullptr) vkUnmapMemory(vk, memory_);
  vkDestroyBuffer(vk, buffer_, nullptr);
  vkFreeMemory(vk, memory_, nullptr);
}

int ExternalBuffer::export_fd() const {
  VkMemoryGetFdInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR;
  info.memory = memory_;
  info.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
  int fd = -1;
  check_vk(vkGetMemoryFdKHR(device_.device(), &info, &fd), "vkGetMemoryFdKHR");
  return fd;
}

ExternalSemaphore::ExternalSemaphore(const Device& device) : device_(device) {
  if (!device.exports_semaphores()) {
    throw Error(ErrorCode::kDevice, "vulkan",
                "vulkan: '" + device.name() + "' does not export semaphores as opaque fds");
  }
  VkExportSemaphoreCreateInfo export_info{};
  export_info.sType = VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO;
  export_info.handleTypes = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
  VkSemaphoreCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  info.pNext = &export_info;
  check_vk(vkCreateSemaphore(device.device(), &info, nullptr, &semaphore_), "vkCreateSemaphore");
}

ExternalSemaphore::~ExternalSemaphore() {
  vkDestroySemaphore(device_.device(), semaphore_, nullptr);
}

int ExternalSemaphore::export_fd() const {
  VkSemaphoreGetFdInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_GET_FD_INFO_KHR;
  info.semaphore = semaphore_;
  info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
  int fd = -1;
  check_vk(vkGetSemaphoreFdKHR(device_.device(), &info, &fd), "vkGetSemaphoreFdKHR");
  return fd;
}

}  // namespace finflex::vulkan

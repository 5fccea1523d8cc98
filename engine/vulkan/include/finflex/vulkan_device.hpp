// A Vulkan device for the external-memory hand-off (library FinFlex::vulkan,
// docs/handoff.md "Zero-copy hand-off"): the memory FinFlex's outputs live in is
// allocated and exported here, then imported by OpenCL (the kernels write it) and by
// the renderer (OpenGL memory objects, or the caller's own Vulkan code).
//
// The Vulkan loader is opened at run time, so a machine without one still runs
// FinFlex: open() throws kDevice naming what is missing and the caller takes the next
// path (finflex/external_outputs.hpp).
//
// Devices are matched by UUID (VkPhysicalDeviceIDProperties::deviceUUID, OpenCL's
// CL_DEVICE_UUID_KHR, OpenGL's GL_DEVICE_UUID_EXT): memory is shared only within one
// physical device.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <vulkan/vulkan_core.h>

namespace finflex::vulkan {

using Uuid = std::array<std::uint8_t, 16>;
// "6d657361-3232-2e33-2e36-000000000000", as vulkaninfo prints it.
std::string to_string(const Uuid& uuid);

class Device {
 public:
  // The physical device whose deviceUUID is `uuid`; without one, the first CPU device
  // (Mesa's lavapipe: the partner of an OpenCL CPU device, which has no UUID). Its
  // logical device has one queue, VK_KHR_external_memory_fd and, where the driver
  // exports binary semaphores as opaque fds, VK_KHR_external_semaphore_fd.
  // Errors (kDevice, "vulkan: ..."): no loader (libvulkan.so.1), no instance, no
  // device with that UUID (the devices there are named), no VK_KHR_external_memory_fd.
  static std::unique_ptr<Device> open(const std::optional<Uuid>& uuid);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }

  const Uuid& uuid() const { return uuid_; }
  const std::string& name() const { return name_; }
  bool is_cpu() const { return cpu_; }
  // Whether binary semaphores can be exported as opaque fds (lavapipe: no).
  bool exports_semaphores() const { return exports_semaphores_; }

  // The index of a memory type in `type_bits` with all of `wanted` (and none of
  // VK_MEMORY_PROPERTY_PROTECTED_BIT); nullopt when none has.
  std::optional<std::uint32_t> memory_type(std::uint32_t type_bits,
                                           VkMemoryPropertyFlags wanted) const;

 private:
  Device() = default;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  Uuid uuid_{};
  std::string name_;
  bool cpu_ = false;
  bool exports_semaphores_ = false;
  VkPhysicalDeviceMemoryProperties memory_{};
};

// Throws kDevice "vulkan: <call> failed: VK_ERROR_..." unless `result` is VK_SUCCESS.
void check_vk(VkResult result, const char* call);

}  // namespace finflex::vulkan

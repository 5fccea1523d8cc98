#include "finflex/vulkan_device.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <volk.h>

#include "finflex/error.hpp"

namespace finflex::vulkan {
namespace {

[[noreturn]] void no_device(const std::string& why) {
  throw Error(ErrorCode::kDevice, "vulkan", "vulkan: " + why);
}

const char* result_name(VkResult result) {
  switch (result) {
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST:
      return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
      return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS:
      return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_INVALID_EXTERNAL_HANDLE:
      return "VK_ERROR_INVALID_EXTERNAL_HANDLE";
    default:
      return "a VkResult";
  }
}

bool has_extension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  for (const VkExtensionProperties& e : extensions) {
    if (std::strcmp(e.extensionName, name) == 0) return true;
  }
  return false;
}

struct PhysicalDevice {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  Uuid uuid{};
  std::string name;
  bool cpu = false;
};

PhysicalDevice describe(VkPhysicalDevice handle) {
  VkPhysicalDeviceIDProperties ids{};
  ids.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  properties.pNext = &ids;
  vkGetPhysicalDeviceProperties2(handle, &properties);
  PhysicalDevice out;
  out.handle = handle;
  std::memcpy(out.uuid.data(), ids.deviceUUID, out.uuid.size());
  out.name = properties.properties.deviceName;
  out.cpu = properties.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  return out;
}

// Whether binary semaphores export as opaque fds (the import side is OpenCL's or GL's).
bool exports_binary_semaphores(VkPhysicalDevice device) {
  if (!has_extension(device, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME)) return false;
  VkPhysicalDeviceExternalSemaphoreInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO;
  info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
  VkExternalSemaphoreProperties properties{};
  properties.sType = VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES;
  vkGetPhysicalDeviceExternalSemaphoreProperties(device, &info, &properties);
  return (properties.externalSemaphoreFeatures & VK_EXTERNAL_SEMAPHORE_FEATURE_EXPORTABLE_BIT) != 0;
}

}  // namespace

std::string to_string(const Uuid& uuid) {
  std::string out;
  char hex[3];
  for (std::size_t k = 0; k < uuid.size(); ++k) {
    if (k == 4 || k == 6 || k == 8 || k == 10) out += '-';
    std::snprintf(hex, sizeof hex, "%02x", uuid[k]);
    out += hex;
  }
  return out;
}

void check_vk(VkResult result, const char* call) {
  if (result != VK_SUCCESS) {
    no_device(std::string(call) + " failed: " + result_name(result) + " (" +
              std::to_string(static_cast<int>(result)) + ")");
  }
}

std::unique_ptr<Device> Device::open(const std::optional<Uuid>& uuid) {
  // The loader once per process (volk keeps its entry points in globals).
  static const VkResult loader = volkInitialize();
  if (loader != VK_SUCCESS) no_device("no Vulkan loader (libvulkan.so.1) could be opened");
  if (volkGetInstanceVersion() < VK_API_VERSION_1_1) no_device("the loader is older than 1.1");

  // Mesa's implicit device-selection layer connects to a Wayland or X display to order
  // the GPUs (and prints an error on a machine without one); FinFlex picks its device
  // by UUID, so the layer is off unless the caller set NODEVICE_SELECT.
  setenv("NODEVICE_SELECT", "1", 0);

  std::unique_ptr<Device> out(new Device());
  VkApplicationInfo application{};
  application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  application.pApplicationName = "FinFlex";
  application.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo instance_info{};
  instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  instance_info.pApplicationInfo = &application;
  check_vk(vkCreateInstance(&instance_info, nullptr, &out->instance_), "vkCreateInstance");
  // Every entry point through the instance's dispatch (valid for each of its
  // devices), so several Devices in one process share them.
  volkLoadInstance(out->instance_);

  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(out->instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> handles(count);
  vkEnumeratePhysicalDevices(out->instance_, &count, handles.data());
  std::string seen;
  PhysicalDevice chosen;
  for (VkPhysicalDevice handle : handles) {
    const PhysicalDevice d = describe(handle);
    seen += (seen.empty() ? "" : ", ") + d.name + " (" + to_string(d.uuid) + ")";
    const bool match = uuid ? d.uuid == *uuid : d.cpu;
    if (match && chosen.handle == VK_NULL_HANDLE) chosen = d;
  }
  if (chosen.handle == VK_NULL_HANDLE) {
    no_device(std::string("no device ") +
              (uuid ? "with UUID " + to_string(*uuid) : std::string("of type CPU")) +
              (seen.empty() ? " (the loader found none)" : " among " + seen));
  }
  if (!has_extension(chosen.handle, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME)) {
    no_device("'" + chosen.name + "' has no " VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
  }
  out->physical_ = chosen.handle;
  out->uuid_ = chosen.uuid;
  out->name_ = chosen.name;
  out->cpu_ = chosen.cpu;
  out->exports_semaphores_ = exports_binary_semaphores(chosen.handle);
  vkGetPhysicalDeviceMemoryProperties(out->physical_, &out->memory_);

  // A queue family with transfers (every graphics or compute family has them).
  vkGetPhysicalDeviceQueueFamilyProperties(out->physical_, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(out->physical_, &count, families.data());
  bool found = false;
  for (std::uint32_t k = 0; k < count && !found; ++k) {
    if (families[k].queueFlags & (VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT)) {
      out->queue_family_ = k;
      found = true;
    }
  }
  if (!found) no_device("'" + chosen.name + "' has no compute queue");

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = out->queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  std::vector<const char*> extensions = {VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME};
  if (out->exports_semaphores_) extensions.push_back(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
  VkDeviceCreateInfo device_info{};
  device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  device_info.ppEnabledExtensionNames = extensions.data();
  check_vk(vkCreateDevice(out->physical_, &device_info, nullptr, &out->device_), "vkCreateDevice");
  vkGetDeviceQueue(out->device_, out->queue_family_, 0, &out->queue_);
  return out;
}

Device::~Device() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);
  }
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

std::optional<std::uint32_t> Device::memory_type(std::uint32_t type_bits,
                                                 VkMemoryPropertyFlags wanted) const {
  for (std::uint32_t k = 0; k < memory_.memoryTypeCount; ++k) {
    const VkMemoryPropertyFlags flags = memory_.memoryTypes[k].propertyFlags;
    if ((type_bits >> k & 1u) == 0 || (flags & VK_MEMORY_PROPERTY_PROTECTED_BIT) != 0) continue;
    if ((flags & wanted) == wanted) return k;
  }
  return std::nullopt;
}

}  // namespace finflex::vulkan

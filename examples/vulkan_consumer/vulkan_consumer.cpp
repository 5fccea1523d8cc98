// The Vulkan consumer of FinFlex's external-memory hand-off (docs/handoff.md): the
// kernels write Vulkan memory; this program, with a Vulkan device of its own on the
// same physical device, imports that memory (a fresh fd), reads FinFlex's planes in a
// compute shader (read_planes.comp) and compares every vertex with the engine's own
// read-back of the same frame. Where OpenCL and Vulkan both have semaphores, the
// frames order themselves on the GPU: the shader waits for the kernels' semaphore and
// signals the consumer's, which the next frame's kernels wait for.
//
//   vulkan_consumer MESH [DEVICE]      e.g. data/blub/fish.obj NVIDIA
//
// Exit status: 0 when every frame matches, 1 when one does not, 2 on an error, 77 when
// the OpenCL device cannot share memory with Vulkan here (the reason printed).
#include <volk.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "finflex/external_outputs.hpp"
#include "finflex/finflex.hpp"
#include "read_planes.spv.h"

namespace {

using finflex::vulkan::check_vk;

// A buffer of the consumer's in host-visible memory, mapped.
struct HostBuffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  HostBuffer(const finflex::vulkan::Device& d, std::size_t bytes) : device(d.device()) {
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    check_vk(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements need{};
    vkGetBufferMemoryRequirements(device, buffer, &need);
    const auto type = d.memory_type(need.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                             VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (!type) throw std::runtime_error("no host-visible memory");
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = need.size;
    allocate.memoryTypeIndex = *type;
    check_vk(vkAllocateMemory(device, &allocate, nullptr, &memory), "vkAllocateMemory");
    check_vk(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    check_vk(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  }
  ~HostBuffer() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
};

// FinFlex's memory imported into the consumer's device: a fresh fd, the exporter's
// size and memory type (an opaque fd carries neither), a dedicated allocation.
struct ImportedBuffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  ImportedBuffer(const finflex::vulkan::Device& d, const finflex::vulkan::ExternalBuffer& from)
      : device(d.device()) {
    VkExternalMemoryBufferCreateInfo external{};
    external.sType = VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO;
    external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.pNext = &external;
    info.size = from.bytes();
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    check_vk(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer (import)");
    const int fd = from.export_fd();
    VkMemoryDedicatedAllocateInfo dedicated{};
    dedicated.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO;
    dedicated.buffer = buffer;
    VkImportMemoryFdInfoKHR import{};
    import.sType = VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR;
    import.pNext = &dedicated;
    import.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    import.fd = fd;
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.pNext = &import;
    allocate.allocationSize = from.memory_bytes();
    allocate.memoryTypeIndex = from.memory_type();
    const VkResult result = vkAllocateMemory(device, &allocate, nullptr, &memory);
    if (result != VK_SUCCESS) close(fd);  // a successful import owns the fd
    check_vk(result, "vkAllocateMemory (import of an opaque fd)");
    check_vk(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory (import)");
  }
  ~ImportedBuffer() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
};

VkSemaphore import_semaphore(const finflex::vulkan::Device& d,
                             const finflex::vulkan::ExternalSemaphore& from) {
  VkSemaphoreCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore semaphore = VK_NULL_HANDLE;
  check_vk(vkCreateSemaphore(d.device(), &info, nullptr, &semaphore), "vkCreateSemaphore");
  VkImportSemaphoreFdInfoKHR import{};
  import.sType = VK_STRUCTURE_TYPE_IMPORT_SEMAPHORE_FD_INFO_KHR;
  import.semaphore = semaphore;
  import.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
  import.fd = from.export_fd();
  check_vk(vkImportSemaphoreFdKHR(d.device(), &import), "vkImportSemaphoreFdKHR");
  return semaphore;
}

// The compute pipeline of read_planes.comp: three storage buffers, 12 bytes of push
// constants.
struct ReadPlanes {
  VkDevice device;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  ReadPlanes(VkDevice d, const VkBuffer (&buffers)[3]) : device(d) {
    VkDescriptorSetLayoutBinding bindings[3]{};
    for (std::uint32_t k = 0; k < 3; ++k) {
      bindings[k].binding = k;
      bindings[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      bindings[k].descriptorCount = 1;
      bindings[k].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = 3;
    set_info.pBindings = bindings;
    check_vk(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout),
             "vkCreateDescriptorSetLayout");
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 3 * sizeof(std::uint32_t)};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &push;
    check_vk(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout),
             "vkCreatePipelineLayout");
    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = sizeof kReadPlanesSpirv;
    module_info.pCode = kReadPlanesSpirv;
    VkShaderModule module = VK_NULL_HANDLE;
    check_vk(vkCreateShaderModule(device, &module_info, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = layout;
    const VkResult made =
        vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    check_vk(made, "vkCreateComputePipelines");
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    check_vk(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    allocate.descriptorPool = pool;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &set_layout;
    check_vk(vkAllocateDescriptorSets(device, &allocate, &set), "vkAllocateDescriptorSets");
    VkDescriptorBufferInfo infos[3]{};
    VkWriteDescriptorSet writes[3]{};
    for (std::uint32_t k = 0; k < 3; ++k) {
      infos[k] = {buffers[k], 0, VK_WHOLE_SIZE};
      writes[k].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[k].dstSet = set;
      writes[k].dstBinding = k;
      writes[k].descriptorCount = 1;
      writes[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[k].pBufferInfo = &infos[k];
    }
    vkUpdateDescriptorSets(device, 3, writes, 0, nullptr);
  }
  ~ReadPlanes() {
    vkDestroyDescriptorPool(device, pool, nullptr);
    vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyPipelineLayout(device, layout, nullptr);
    vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
  }
};

int run(const std::string& mesh_path, const std::string& device_name) {
  finflex::Context context(device_name);
  const finflex::Mesh mesh = finflex::load_mesh(mesh_path);
  const finflex::RiggedMesh fish = finflex::RiggedMesh::single_bend(
      mesh, finflex::find_body_frame(mesh), finflex::BendMode::kExact);
  finflex::ClDeformer deformer(context, fish);
  finflex::ExternalChoice choice = finflex::choose_external_device(context);
  if (!choice.device) {
    std::printf("vulkan_consumer: no external memory on '%s': %s\n",
                context.description().device_name.c_str(), choice.why_not.c_str());
    return 77;
  }
  const std::size_t instances = 24;
  finflex::OutputLayout layout = deformer.layout(instances);
  layout.tangents.reset();
  finflex::ExternalOutputs outputs(deformer, instances, layout, *choice.device);
  finflex::DeviceBatch oracle = deformer.allocate(instances);

  // The consumer: a Vulkan device of its own on the same physical device.
  const std::unique_ptr<finflex::vulkan::Device> consumer =
      finflex::vulkan::Device::open(choice.device->uuid());
  const ImportedBuffer planes(*consumer, outputs.buffer(outputs.buffer_of(0)));
  const std::vector<std::uint32_t>& slots = deformer.slot_of_vertex();
  const std::size_t vertices = slots.size();
  HostBuffer slot_buffer(*consumer, slots.size() * sizeof(std::uint32_t));
  std::memcpy(slot_buffer.mapped, slots.data(), slots.size() * sizeof(std::uint32_t));
  HostBuffer read(*consumer, instances * vertices * 3 * sizeof(float));
  const VkBuffer buffers[3] = {planes.buffer, slot_buffer.buffer, read.buffer};
  const ReadPlanes pipeline(consumer->device(), buffers);
  const bool ordered = outputs.device_ordered();
  const VkSemaphore kernels_done =
      ordered ? import_semaphore(*consumer, *outputs.kernels_done()) : VK_NULL_HANDLE;
  const VkSemaphore consumer_done =
      ordered ? import_semaphore(*consumer, *outputs.consumer_done()) : VK_NULL_HANDLE;

  VkCommandPoolCreateInfo pool_info{};

  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.queueFamilyIndex = consumer->queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  check_vk(vkCreateCommandPool(consumer->device(), &pool_info, nullptr, &pool),
           "vkCreateCommandPool");
  VkCommandBufferAllocateInfo command_info{};
  command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  command_info.commandPool = pool;
  command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_info.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  check_vk(vkAllocateCommandBuffers(consumer->device(), &command_info, &commands),
           "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  check_vk(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, 1,
                          &pipeline.set, 0, nullptr);
  const std::uint32_t shape[3] = {static_cast<std::uint32_t>(layout.positions.plane_stride),
                                  static_cast<std::uint32_t>(vertices),
                                  static_cast<std::uint32_t>(instances)};
  vkCmdPushConstants(commands, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof shape,
                     shape);
  vkCmdDispatch(commands, static_cast<std::uint32_t>((vertices + 63) / 64),
                static_cast<std::uint32_t>(instances), 1);
  check_vk(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

  int mismatched_frames = 0;
  finflex::RigParameters values(fish, instances);
  for (int frame = 0; frame < 3; ++frame) {
    for (std::size_t i = 0; i < instances; ++i) {
      values.set(i, "m", 0.12f * std::sin(0.7f * float(i) + 0.9f * float(frame)));
    }
    finflex::ClJob job;
    job.instances = instances;
    job.parameters = values.view();
    job.outputs = &outputs.batch();
    outputs.enqueue(job);
    job.outputs = &oracle;
    deformer.enqueue(job);
    const finflex::DeformedBatch<float> expected = deformer.read(oracle);

    // The shader reads the frame: after the kernels' semaphore, or once it is there.
    if (!ordered) outputs.wait_for_frame();
    const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.waitSemaphoreCount = ordered ? 1 : 0;
    submit.pWaitSemaphores = &kernels_done;
    submit.pWaitDstStageMask = &stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    submit.signalSemaphoreCount = ordered ? 1 : 0;
    submit.pSignalSemaphores = &consumer_done;
    check_vk(vkQueueSubmit(consumer->queue(), 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
    if (ordered) outputs.consumer_signalled();  // the next frame's kernels wait for it
    check_vk(vkQueueWaitIdle(consumer->queue()), "vkQueueWaitIdle");

    const auto* got = static_cast<const float*>(read.mapped);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < instances; ++i) {
      for (std::size_t v = 0; v < vertices; ++v) {
        const auto p = expected.position(i, v);
        for (int c = 0; c < 3; ++c)
          differing += got[(i * vertices + v) * 3 + std::size_t(c)] != p[c];
      }
    }
    std::printf("frame %d: %zu of %zu position components differ\n", frame, differing,
                instances * vertices * 3);
    mismatched_frames += differing != 0;
  }
  std::printf("vulkan_consumer: '%s' -> %s (%s), %s; %d of 3 frames equal the engine's read-back\n",
              context.description().device_name.c_str(), choice.device->name().c_str(),
              finflex::to_string(outputs.import()),
              ordered ? "semaphores order the frames on the device" : "host waits",
              3 - mismatched_frames);
  vkDestroyCommandPool(consumer->device(), pool, nullptr);
  if (ordered) {
    vkDestroySemaphore(consumer->device(), kernels_done, nullptr);
    vkDestroySemaphore(consumer->device(), consumer_done, nullptr);
  }
  return mismatched_frames == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: vulkan_consumer MESH [DEVICE]\n");
    return 2;
  }
  try {
    return run(argv[1], argc == 3 ? argv[2] : "");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vulkan_consumer: %s\n", e.what());
    return 2;
  }
}

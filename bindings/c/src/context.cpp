// Devices and contexts.
#include <algorithm>
#include <cstring>

#include "handles.hpp"

namespace {

void copy_text(char* out, std::size_t size, const std::string& text) {
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(out, text.data(), n);
  out[n] = '\0';
}

void describe(const finflex::DeviceDescription& d, finflex_device_info* info) {
  *info = finflex_device_info{};
  info->platform_index = d.platform_index;
  info->device_index = d.device_index;
  copy_text(info->platform_name, sizeof info->platform_name, d.platform_name);
  copy_text(info->device_name, sizeof info->device_name, d.device_name);
  copy_text(info->type, sizeof info->type, d.type);
  copy_text(info->version, sizeof info->version, d.version);
  info->global_memory_bytes = d.global_memory_bytes;
  info->max_allocation_bytes = d.max_allocation_bytes;
  info->is_default = d.is_default ? 1 : 0;
}

}  // namespace

using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

extern "C" {

finflex_status finflex_list_devices(finflex_device_info* devices, size_t capacity, size_t* count) {
  return guarded(nullptr, [&] {
    require(count, "count");
    if (capacity > 0) require(devices, "devices");
    const std::vector<finflex::DeviceDescription> found = finflex::list_devices();
    for (std::size_t i = 0; i < found.size() && i < capacity; ++i) describe(found[i], &devices[i]);
    *count = found.size();
  });
}

finflex_status finflex_context_create(const char* device, finflex_context** context) {
  return finflex::c::create(nullptr, context, "context", [&] {
    auto handle = std::make_unique<finflex_context>();
    handle->context = std::make_shared<finflex::Context>(device == nullptr ? "" : device);
    return handle;
  });
}

void finflex_context_destroy(finflex_context* context) { delete context; }

const finflex_error* finflex_context_error(const finflex_context* context) {
  return slot_of(context);
}

finflex_status finflex_context_device(finflex_context* context, finflex_device_info* info) {
  return guarded(slot_of(context), [&] {
    require(context, "context");
    describe(context->context->description(), require(info, "info"));
  });
}

finflex_status finflex_context_finish(finflex_context* context) {
  return guarded(slot_of(context), [&] {
    finflex::check_cl(require(context, "context")->context->queue().finish(), "clFinish");
  });
}

void* finflex_context_cl_context(const finflex_context* context) {
  return context == nullptr ? nullptr : context->context->context()();
}

void* finflex_context_cl_queue(const finflex_context* context) {
  return context == nullptr ? nullptr : context->context->queue()();
}

}  // extern "C"

// Caller-owned host outputs: checks and copies.
#include "host_outputs.hpp"

#include <cstdint>
#include <cstring>
#include <string>

namespace finflex::c {
namespace {

[[noreturn]] void reject(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + " " + message);
}

void check_attribute(const finflex_attribute_layout& a, const char* name, std::size_t instances,
                     std::size_t vertices) {
  if (a.data == nullptr || instances == 0 || vertices == 0) return;
  const std::string base = std::string("outputs.") + name;
  if (a.format != FINFLEX_FORMAT_FLOAT32) {
    reject(base + ".format", "= " + std::to_string(static_cast<int>(a.format)) +
                                 ": host outputs are FINFLEX_FORMAT_FLOAT32 (0)");
  }
  if (reinterpret_cast<std::uintptr_t>(a.data) % 4 != 0) {
    reject(base + ".data", "is not 4-byte aligned: float32 elements need it");
  }
  if (a.vertex_stride < 12 || a.vertex_stride % 4 != 0) {
    reject(base + ".vertex_stride",
           "= " + std::to_string(a.vertex_stride) +
               " bytes: it must be at least 12 (x, y, z) and a multiple of 4");
  }
  if (a.instance_stride < a.vertex_stride * vertices || a.instance_stride % 4 != 0) {
    reject(base + ".instance_stride", "= " + std::to_string(a.instance_stride) +
                                          " bytes: it must be a multiple of 4 and at least " +
                                          std::to_string(vertices) + " vertices x " +
                                          std::to_string(a.vertex_stride) +
                                          " bytes = " + std::to_string(a.vertex_stride * vertices));
  }
  const std::size_t needed =
      a.instance_stride * (instances - 1) + a.vertex_stride * (vertices - 1) + 12;
  if (a.capacity < needed) {
    reject(base + ".capacity", "= " + std::to_string(a.capacity) +
                                   " bytes is too small: " + std::to_string(instances) +
                                   " instances of " + std::to_string(vertices) + " vertices need " +
                                   std::to_string(needed) + " bytes");
  }
}

float* element(const finflex_attribute_layout& a, std::size_t instance, std::size_t vertex) {
  return reinterpret_cast<float*>(static_cast<char*>(a.data) + instance * a.instance_stride +
                                  vertex * a.vertex_stride);
}

template <typename T>
void store(const finflex::DeformedBatch<T>& batch, const finflex_host_outputs& outputs) {
  const std::size_t instances = batch.shape.instance_count;
  const std::size_t vertices = batch.shape.vertex_count;
  using Gather = typename finflex::DeformedBatch<T>::Vec3 (finflex::DeformedBatch<T>::*)(
      std::size_t, std::size_t) const;
  const auto copy = [&](const finflex_attribute_layout& a, Gather gather) {
    if (a.data == nullptr) return;
    for (std::size_t i = 0; i < instances; ++i) {
      for (std::size_t v = 0; v < vertices; ++v) {
        const glm::vec3 value((batch.*gather)(i, v));
        std::memcpy(element(a, i, v), &value[0], 12);
      }
    }
  };
  copy(outputs.positions, &finflex::DeformedBatch<T>::position);
  copy(outputs.normals, &finflex::DeformedBatch<T>::normal);
  if (batch.shape.tangents) copy(outputs.tangents, &finflex::DeformedBatch<T>::tangent);
}

}  // namespace

void check_outputs(const finflex_host_outputs* outputs, std::size_t instances, std::size_t vertices,
                   bool mesh_has_tangents) {
  require(outputs, "outputs");
  check_attribute(outputs->positions, "positions", instances, vertices);
  check_attribute(outputs->normals, "normals", instances, vertices);
  if (outputs->tangents.data != nullptr && !mesh_has_tangents) {
    reject("outputs.tangents.data", "is set, but the mesh has no tangents");
  }
  check_attribute(outputs->tangents, "tangents", instances, vertices);
}

glm::vec3 load_element(const finflex_attribute_layout& layout, std::size_t instance,
                       std::size_t vertex) {
  glm::vec3 value;
  std::memcpy(&value[0], element(layout, instance, vertex), 12);
  return value;
}

void store_outputs(const finflex::DeformedBatch<float>& batch,
                   const finflex_host_outputs& outputs) {
  store(batch, outputs);
}
void store_outputs(const finflex::DeformedBatch<double>& batch,
                   const finflex_host_outputs& outputs) {
  store(batch, outputs);
}

}  // namespace finflex::c

extern "C" void finflex_attribute_layout_packed(void* data, size_t instances, size_t vertices,
                                                finflex_attribute_layout* layout) {
  if (layout == nullptr) return;
  layout->data = data;
  layout->vertex_stride = 12;
  layout->instance_stride = 12 * vertices;
  layout->capacity = 12 * vertices * instances;
  layout->format = FINFLEX_FORMAT_FLOAT32;
}

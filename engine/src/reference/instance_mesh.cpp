#include "finflex/instance_mesh.hpp"

#include <string>

#include "finflex/error.hpp"

namespace finflex {
namespace {

template <typename T>
Mesh instance_mesh_impl(const Mesh& rest, const DeformedBatch<T>& batch, std::size_t instance) {
  if (instance >= batch.shape.instance_count) {
    throw Error(ErrorCode::kInvalidArgument, "instance",
                "instance = " + std::to_string(instance) + " is out of range (batch of " +
                    std::to_string(batch.shape.instance_count) + ")");
  }
  if (batch.shape.vertex_count != rest.vertex_count()) {
    throw Error(ErrorCode::kInvalidArgument, "batch",
                "the batch has " + std::to_string(batch.shape.vertex_count) +
                    " vertices per instance, the rest mesh " + std::to_string(rest.vertex_count()));
  }
  Mesh out = rest;
  const bool tangents = rest.has_tangents() && batch.shape.tangents;
  for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
    out.positions[v] = glm::vec3(batch.position(instance, v));
    out.normals[v] = glm::vec3(batch.normal(instance, v));
    if (tangents)
      out.tangents[v] = glm::vec4(glm::vec3(batch.tangent(instance, v)), rest.tangents[v].w);
  }
  return out;
}

}  // namespace

Mesh instance_mesh(const Mesh& rest, const DeformedBatch<float>& batch, std::size_t instance) {
  return instance_mesh_impl(rest, batch, instance);
}

Mesh instance_mesh(const Mesh& rest, const DeformedBatch<double>& batch, std::size_t instance) {
  return instance_mesh_impl(rest, batch, instance);
}

}  // namespace finflex

// Mesh assembly shared by the readers (see mesh_io_builder.hpp).
#include "io/builder.hpp"

#include <limits>

#include "finflex/error.hpp"

namespace finflex::io {

std::uint32_t MeshBuilder::add_vertex(const glm::vec3& position) {
  if (positions_.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw Error(ErrorCode::kFormat, "positions", "positions: more than 2^32 - 1 vertices");
  }
  positions_.push_back(position);
  return static_cast<std::uint32_t>(positions_.size() - 1);
}

void MeshBuilder::add_normal(std::uint32_t vertex, const glm::vec3& normal) {
  if (normals_.size() <= vertex) normals_.resize(positions_.size());
  NormalSlot& slot = normals_[vertex];
  if (slot.count == 0) slot.first = normal;
  slot.all_equal = slot.all_equal && normal == slot.first;
  slot.sum += glm::dvec3(normal);
  ++slot.count;
}

void MeshBuilder::add_texcoord(std::uint32_t vertex, const glm::vec2& texcoord) {
  if (texcoords_.size() <= vertex) {
    texcoords_.resize(positions_.size(), glm::vec2(0.0f));
    has_texcoord_.resize(positions_.size(), false);
  }
  if (has_texcoord_[vertex]) return;  // first one wins: a per-vertex texcoord cannot hold seams
  has_texcoord_[vertex] = true;
  texcoords_[vertex] = texcoord;
}

void MeshBuilder::add_polygon(const std::vector<std::uint32_t>& corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {  // fan around corners[0]
    indices_.insert(indices_.end(), {corners[0], corners[k], corners[k + 1]});
  }
}

Mesh MeshBuilder::finish() {
  Mesh mesh;
  mesh.positions = std::move(positions_);
  mesh.indices = std::move(indices_);
  if (!normals_.empty()) {
    normals_.resize(mesh.positions.size());
    compute_vertex_normals(mesh);  // the fallback for vertices without a usable normal
    for (std::size_t v = 0; v < normals_.size(); ++v) {
      const NormalSlot& slot = normals_[v];
      const glm::dvec3 n = slot.all_equal ? glm::dvec3(slot.first) : slot.sum;
      const double length = glm::length(n);
      if (slot.count > 0 && length > 0.0) mesh.normals[v] = glm::vec3(n / length);
    }
  }
  if (!texcoords_.empty()) {
    texcoords_.resize(mesh.positions.size(), glm::vec2(0.0f));
    mesh.texcoords = std::move(texcoords_);
  }
  return mesh;
}

}  // namespace finflex::io

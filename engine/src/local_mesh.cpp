#include "finflex/local_mesh.hpp"

#include <cmath>

#include "finflex/error.hpp"

namespace finflex {

LocalMesh make_local_mesh(const Mesh& mesh, const BodyFrame& frame) {
  validate_mesh(mesh);
  frame.validate();
  LocalMesh local;
  local.frame = frame;
  local.indices = mesh.indices;
  const std::size_t n = mesh.vertex_count();
  local.positions.resize(n);
  local.normals.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    local.positions[v] = frame.point_to_local(glm::dvec3(mesh.positions[v]));
    local.normals[v] = glm::normalize(frame.vector_to_local(glm::dvec3(mesh.normals[v])));
    local.x_max = std::max(local.x_max, std::fabs(local.positions[v].x));
  }
  if (mesh.has_tangents()) {
    local.tangents.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      const glm::dvec4 t(mesh.tangents[v]);
      const glm::dvec3 xyz = glm::normalize(frame.vector_to_local(glm::dvec3(t)));
      local.tangents[v] = glm::dvec4(xyz, t.w < 0.0 ? -1.0 : 1.0);
    }
  }
  if (!(local.x_max > 0.0)) {
    throw Error(ErrorCode::kInvalidMesh, "positions",
                "the mesh has no extent along the spine (x_max = 0 in the body frame)");
  }
  return local;
}

}  // namespace finflex

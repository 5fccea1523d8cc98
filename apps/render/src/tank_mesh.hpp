// The tank as triangles: the inside of the cylindrical wall (normals pointing in, a
// lighter band at the rim) and the floor disc (normals up, a dark drain at the centre).
// Counter-clockwise seen from the side the normals point to.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/scene.hpp"

namespace finflex::render::detail {

struct TankVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;
};

struct TankMesh {
  std::vector<TankVertex> vertices;
  std::vector<std::uint32_t> indices;
};

TankMesh make_tank_mesh(const Tank& tank);

}  // namespace finflex::render::detail

#include "tank_mesh.hpp"

#include <cmath>
#include <vector>

namespace finflex::render::detail {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kRimBand = 0.06f;      // metres of lighter wall below the rim
constexpr float kDrainRadius = 0.08f;  // of the tank's radius
constexpr float kDrainAlbedo = 0.4f;   // of the floor's albedo
// Rows of the wall and rings of the floor: small enough triangles that view rays
// refracted per vertex (Scene::view_refraction) stay within a fraction of a pixel
// inside them (docs/rendering.md "Refraction").
constexpr int kWallRows = 16;
constexpr int kFloorRings = 48;

glm::vec3 on_circle(float radius, float angle, float y) {
  return {radius * std::cos(angle), y, radius * std::sin(angle)};
}

// A band of the wall between heights y0 < y1 in `rows` rows, one colour, facing the axis.
void add_wall_band(const Tank& tank, float y0, float y1, int rows, const glm::vec3& albedo,
                   TankMesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  const auto columns = static_cast<std::uint32_t>(rows + 1);  // vertices up each column
  for (int s = 0; s <= tank.segments; ++s) {
    const float angle = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(tank.segments);
    const glm::vec3 inward{-std::cos(angle), 0.0f, -std::sin(angle)};
    for (int k = 0; k <= rows; ++k) {
      const float y = y0 + (y1 - y0) * static_cast<float>(k) / static_cast<float>(rows);
      mesh.vertices.push_back({on_circle(tank.radius, angle, y), inward, albedo});
    }
  }
  for (std::uint32_t s = 0; s < static_cast<std::uint32_t>(tank.segments); ++s) {
    for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(rows); ++k) {
      const std::uint32_t b0 = first + columns * s + k;
      const std::uint32_t t0 = b0 + 1;
      const std::uint32_t b1 = b0 + columns;
      const std::uint32_t t1 = b1 + 1;
      mesh.indices.insert(mesh.indices.end(), {b0, b1, t1, b0, t1, t0});
    }
  }
}

// The floor: a centre vertex and rings at the given radii, each with its own albedo.
void add_floor(const Tank& tank, TankMesh& mesh) {
  const glm::vec3 up{0.0f, 1.0f, 0.0f};
  const glm::vec3 drain = tank.floor_albedo * kDrainAlbedo;
  std::vector<float> radii{kDrainRadius * tank.radius, (kDrainRadius + 0.02f) * tank.radius};
  std::vector<glm::vec3> albedos{drain, tank.floor_albedo};
  for (int k = 1; k <= kFloorRings; ++k) {
    const float from = radii[1];
    radii.push_back(from + (tank.radius - from) * static_cast<float>(k) / float(kFloorRings));
    albedos.push_back(tank.floor_albedo);
  }
  const auto rings = static_cast<std::uint32_t>(radii.size());
  const auto centre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back({glm::vec3(0.0f), up, drain});
  for (std::uint32_t ring = 0; ring < rings; ++ring) {
    for (int s = 0; s < tank.segments; ++s) {
      const float angle = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(tank.segments);
      mesh.vertices.push_back({on_circle(radii[ring], angle, 0.0f), up, albedos[ring]});
    }
  }
  const auto n = static_cast<std::uint32_t>(tank.segments);
  const auto at = [&](std::uint32_t ring, std::uint32_t s) {
    return centre + 1 + ring * n + s % n;
  };
  for (std::uint32_t s = 0; s < n; ++s) {
    mesh.indices.insert(mesh.indices.end(), {centre, at(0, s + 1), at(0, s)});
    for (std::uint32_t ring = 0; ring + 1 < rings; ++ring) {
      mesh.indices.insert(mesh.indices.end(), {at(ring, s), at(ring + 1, s + 1), at(ring + 1, s),
                                               at(ring, s), at(ring, s + 1), at(ring + 1, s + 1)});
    }
  }
}

}  // namespace

TankMesh make_tank_mesh(const Tank& tank) {
  TankMesh mesh;
  const float rim = std::fmax(tank.wall_height - kRimBand, 0.0f);
  add_wall_band(tank, 0.0f, rim, kWallRows, tank.wall_albedo, mesh);
  add_wall_band(tank, rim, tank.wall_height, 1, glm::min(tank.wall_albedo * 1.6f, glm::vec3(0.9f)),
                mesh);
  add_floor(tank, mesh);
  return mesh;
}

}  // namespace finflex::render::detail

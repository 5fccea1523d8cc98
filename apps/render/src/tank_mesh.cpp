#include "tank_mesh.hpp"

#include <cmath>

namespace finflex::render::detail {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kRimBand = 0.06f;      // metres of lighter wall below the rim
constexpr float kDrainRadius = 0.08f;  // of the tank's radius
constexpr float kDrainAlbedo = 0.4f;   // of the floor's albedo

glm::vec3 on_circle(float radius, float angle, float y) {
  return {radius * std::cos(angle), y, radius * std::sin(angle)};
}

// A band of the wall between heights y0 < y1, one colour, facing the axis.
void add_wall_band(const Tank& tank, float y0, float y1, const glm::vec3& albedo, TankMesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int s = 0; s <= tank.segments; ++s) {
    const float angle = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(tank.segments);
    const glm::vec3 inward{-std::cos(angle), 0.0f, -std::sin(angle)};
    mesh.vertices.push_back({on_circle(tank.radius, angle, y0), inward, albedo});
    mesh.vertices.push_back({on_circle(tank.radius, angle, y1), inward, albedo});
  }
  for (std::uint32_t s = 0; s < static_cast<std::uint32_t>(tank.segments); ++s) {
    const std::uint32_t b0 = first + 2 * s;
    const std::uint32_t t0 = b0 + 1;
    const std::uint32_t b1 = b0 + 2;
    const std::uint32_t t1 = b0 + 3;
    mesh.indices.insert(mesh.indices.end(), {b0, b1, t1, b0, t1, t0});
  }
}

// The floor: a centre vertex and rings at the given radii, each with its own albedo.
void add_floor(const Tank& tank, TankMesh& mesh) {
  const glm::vec3 up{0.0f, 1.0f, 0.0f};
  const glm::vec3 drain = tank.floor_albedo * kDrainAlbedo;
  const float radii[] = {kDrainRadius * tank.radius, (kDrainRadius + 0.02f) * tank.radius,
                         tank.radius};
  const glm::vec3 albedos[] = {drain, tank.floor_albedo, tank.floor_albedo};
  const auto centre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back({glm::vec3(0.0f), up, drain});
  for (int ring = 0; ring < 3; ++ring) {
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
    for (std::uint32_t ring = 0; ring + 1 < 3; ++ring) {
      mesh.indices.insert(mesh.indices.end(), {at(ring, s), at(ring + 1, s + 1), at(ring + 1, s),
                                               at(ring, s), at(ring, s + 1), at(ring + 1, s + 1)});
    }
  }
}

}  // namespace

TankMesh make_tank_mesh(const Tank& tank) {
  TankMesh mesh;
  const float rim = std::fmax(tank.wall_height - kRimBand, 0.0f);
  add_wall_band(tank, 0.0f, rim, tank.wall_albedo, mesh);
  add_wall_band(tank, rim, tank.wall_height, glm::min(tank.wall_albedo * 1.6f, glm::vec3(0.9f)),
                mesh);
  add_floor(tank, mesh);
  return mesh;
}

}  // namespace finflex::render::detail

#include "render/scene.hpp"

#include "checks.hpp"

namespace finflex::render {

const char* to_string(ViewRefraction refraction) {
  switch (refraction) {
    case ViewRefraction::kSurface:
      return "surface";
    case ViewRefraction::kPort:
      return "port";
    case ViewRefraction::kNone:
      break;
  }
  return "none";
}

void Scene::validate() const {
  using namespace detail;
  require_positive("scene.tank.radius", tank.radius);
  require_positive("scene.tank.wall_height", tank.wall_height);
  require_positive("scene.tank.water_depth", tank.water_depth);
  if (tank.water_depth > tank.wall_height) {
    invalid("scene.tank.water_depth",
            to_text(tank.water_depth) + " is above the wall_height " + to_text(tank.wall_height));
  }
  require_non_negative("scene.tank.wall_albedo", tank.wall_albedo);
  require_non_negative("scene.tank.floor_albedo", tank.floor_albedo);
  require_in_range("scene.tank.segments", tank.segments, 8, 4096);
  require_in_range("scene.rows.count", rows.count, 1, 4096);
  require_in_range("scene.rows.columns", rows.columns, 1, 4096);
  require_finite("scene.rows.spacing", rows.spacing);
  if (rows.count > 1 && rows.spacing < 2.0f * tank.radius) {
    invalid("scene.rows.spacing", to_text(rows.spacing) + " is less than the tank's diameter " +
                                      to_text(2.0f * tank.radius));
  }
  require_non_negative("scene.water.absorption", water.absorption);
  require_non_negative("scene.water.scattering", water.scattering);
  require_in_range("scene.water.phase_asymmetry", water.phase_asymmetry, 0.0f, 0.99f);
  require_in_range("scene.water.refractive_index", water.refractive_index, 1.0f, 2.0f);
  require_finite("scene.lighting.direction_to_light", lighting.direction_to_light);
  if (glm::length(lighting.direction_to_light) <= 0.0f) {
    invalid("scene.lighting.direction_to_light", "is zero");
  }
  require_non_negative("scene.lighting.key_colour", lighting.key_colour);
  require_non_negative("scene.lighting.sky_ambient", lighting.sky_ambient);
  require_non_negative("scene.lighting.ground_ambient", lighting.ground_ambient);
  require_in_range("scene.lighting.specular", lighting.specular, 0.0f, 1.0f);
  require_in_range("scene.lighting.shininess", lighting.shininess, 1.0f, 10000.0f);
  require_non_negative("scene.background", background);
  require_positive("scene.port.distance", port.distance);
  require_in_range("scene.port.thickness", port.thickness, 0.0f, 1.0f);
  require_in_range("scene.port.refractive_index", port.refractive_index, 1.0f, 2.0f);
}

}  // namespace finflex::render

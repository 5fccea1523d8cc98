#include "scene_uniforms.hpp"

#include <algorithm>
#include <cmath>

namespace finflex::render::detail {

SceneBlock make_scene_block(const Scene& scene, const Camera& camera, float aspect) {
  const Lighting& light = scene.lighting;
  SceneBlock block;
  block.view_projection = projection_matrix(camera, aspect) * view_matrix(camera);
  block.camera_position = glm::vec4(camera.position, 1.0f);
  block.camera_forward = glm::vec4(glm::normalize(camera.target - camera.position), 0.0f);
  block.light_direction = glm::vec4(glm::normalize(light.direction_to_light), 0.0f);
  block.key_colour = glm::vec4(light.key_colour, light.specular);
  block.sky_ambient = glm::vec4(light.sky_ambient, light.shininess);
  block.ground_ambient = glm::vec4(light.ground_ambient, scene.tank.water_depth);
  const Water& water = scene.water;
  block.water_attenuation = glm::vec4(water.attenuation(), scene.tank.radius);
  block.water_scattering = glm::vec4(water.scattering, water.phase_asymmetry);
  // Snell's law at the flat surface: the horizontal part shrinks by the index.
  const glm::vec3 to_light = glm::normalize(light.direction_to_light);
  const glm::vec2 across = glm::vec2(to_light.x, to_light.z) / water.refractive_index;
  const float up = std::sqrt(std::max(1.0f - glm::dot(across, across), 0.0f));
  block.key_in_water = glm::vec4(across.x, up, across.y, water.refractive_index);
  block.key_downwelling = glm::vec4(downwelling_attenuation(water, up), 0.0f);
  block.ambient_downwelling = glm::vec4(downwelling_attenuation(water, 1.0f), 0.0f);
  block.tank_rows =
      glm::vec4(float(scene.rows.count), float(scene.rows.columns), scene.rows.spacing, 0.0f);
  block.refraction = glm::vec4(float(static_cast<int>(scene.view_refraction)), scene.port.distance,
                               scene.port.thickness, scene.port.refractive_index);
  return block;
}

}  // namespace finflex::render::detail

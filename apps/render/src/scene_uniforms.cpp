#include "scene_uniforms.hpp"

namespace finflex::render::detail {

SceneBlock make_scene_block(const Scene& scene, const Camera& camera, float aspect) {
  const Lighting& light = scene.lighting;
  SceneBlock block;
  block.view_projection = projection_matrix(camera, aspect) * view_matrix(camera);
  block.camera_position = glm::vec4(camera.position, 1.0f);
  block.light_direction = glm::vec4(glm::normalize(light.direction_to_light), 0.0f);
  block.key_colour = glm::vec4(light.key_colour, light.specular);
  block.sky_ambient = glm::vec4(light.sky_ambient, light.shininess);
  block.ground_ambient = glm::vec4(light.ground_ambient, 0.0f);
  block.fog_colour = glm::vec4(scene.water.fog_colour, scene.tank.water_depth);
  block.extinction = glm::vec4(scene.water.extinction, scene.tank.radius);
  block.tank_rows =
      glm::vec4(float(scene.rows.count), float(scene.rows.columns), scene.rows.spacing, 0.0f);
  return block;
}

}  // namespace finflex::render::detail

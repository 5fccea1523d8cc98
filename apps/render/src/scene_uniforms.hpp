// The Scene uniform block of shaders/scene_block.glsl, as std140 lays it out.
#pragma once

#include <glm/glm.hpp>

#include "render/camera.hpp"
#include "render/scene.hpp"

namespace finflex::render::detail {

struct SceneBlock {
  glm::mat4 view_projection;
  glm::vec4 camera_position;
  glm::vec4 camera_forward;
  glm::vec4 light_direction;
  glm::vec4 key_colour;         // w: specular strength
  glm::vec4 sky_ambient;        // w: shininess
  glm::vec4 ground_ambient;     // w: height of the water surface
  glm::vec4 water_attenuation;  // w: the tank's radius
  glm::vec4 water_scattering;   // w: phase asymmetry
  glm::vec4 key_in_water;
  glm::vec4 key_downwelling;
  glm::vec4 ambient_downwelling;
  glm::vec4 tank_rows;   // x: count, y: columns, z: spacing
  glm::vec4 refraction;  // x: ViewRefraction (0, 1, 2); yzw: the port's distance, thickness, index
};
static_assert(sizeof(SceneBlock) == 64 + 13 * 16, "std140: a mat4 and thirteen vec4");

SceneBlock make_scene_block(const Scene& scene, const Camera& camera, float aspect);

}  // namespace finflex::render::detail

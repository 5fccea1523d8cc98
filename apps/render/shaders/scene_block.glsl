// The frame's shared values (std140), one uniform buffer bound to every program at
// binding 0; written by scene_uniforms.cpp from render::Scene and render::Camera.
layout(std140) uniform Scene {
  mat4 u_view_projection;
  vec4 u_camera_position;  // xyz: world metres
  vec4 u_light_direction;  // xyz: unit, towards the key light
  vec4 u_key_colour;       // rgb: key light irradiance (linear); w: specular strength
  vec4 u_sky_ambient;      // rgb: ambient from above; w: Blinn-Phong exponent
  vec4 u_ground_ambient;   // rgb: ambient from below
  vec4 u_fog_colour;       // rgb: what far water fades to; w: height of the water surface
  vec4 u_extinction;       // rgb: water's extinction per metre; w: the tank's radius
};

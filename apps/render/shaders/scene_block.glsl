// The frame's shared values (std140), one uniform buffer bound to every program at
// binding 0; written by scene_uniforms.cpp from render::Scene and render::Camera.
layout(std140) uniform Scene {
  mat4 u_view_projection;
  vec4 u_camera_position;  // xyz: world metres
  vec4 u_camera_forward;   // xyz: unit, the camera's axis
  vec4 u_light_direction;  // xyz: unit, towards the key light
  vec4 u_key_colour;       // rgb: key light irradiance (linear); w: specular strength
  vec4 u_sky_ambient;      // rgb: ambient from above; w: Blinn-Phong exponent
  vec4 u_ground_ambient;   // rgb: ambient from below; w: height of the water surface
  vec4 u_water_attenuation;  // rgb: beam attenuation c = a + b per metre; w: the tank's radius
  vec4 u_water_scattering;   // rgb: scattering b per metre; w: phase asymmetry g
  vec4 u_key_in_water;       // xyz: unit, towards the key light below the surface; w: the
                             // water's refractive index
  vec4 u_key_downwelling;    // rgb: the key light's diffuse attenuation K_d per metre of depth
  vec4 u_ambient_downwelling;  // rgb: the ambient light's
  vec4 u_tank_rows;        // x: tanks, y: tanks per row, z: spacing of their axes (m)
  vec4 u_refraction;       // x: 0 straight, 1 at the surface, 2 at the port; yzw: the port's
                           // distance (m), thickness (m), refractive index
};

// Tank t's axis on the floor, (x, z) (render/scene.hpp TankRows).
vec2 tank_axis(int t) {
  int columns = int(u_tank_rows.y);
  return u_tank_rows.z * vec2(float(t % columns), -float(t / columns));
}

// The axis of the tank nearest p: the one whose water p is in.
vec2 nearest_tank_axis(vec3 p) {
  int count = int(u_tank_rows.x);
  int columns = int(u_tank_rows.y);
  if (count <= 1) return vec2(0.0);
  int rows = (count + columns - 1) / columns;
  int row = clamp(int(round(-p.z / u_tank_rows.z)), 0, rows - 1);
  int in_row = min(columns, count - row * columns);
  int column = clamp(int(round(p.x / u_tank_rows.z)), 0, in_row - 1);
  return tank_axis(row * columns + column);
}

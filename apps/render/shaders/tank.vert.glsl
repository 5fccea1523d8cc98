// The tank's wall and floor: ordinary vertex attributes around tank 0's axis; instance
// t is tank t (render/scene.hpp TankRows).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;

out vec3 v_world_position;
#ifdef FINFLEX_REFRACTION
out vec3 v_view_origin;  // refraction.glsl apparent_position
#endif
out vec3 v_normal;
out vec3 v_albedo;

void main() {
  vec2 axis = tank_axis(gl_InstanceID);
  v_world_position = a_position + vec3(axis.x, 0.0, axis.y);
  v_normal = a_normal;
  v_albedo = a_albedo;
#ifdef FINFLEX_REFRACTION
  gl_Position = u_view_projection * vec4(apparent_position(v_world_position, v_view_origin), 1.0);
#else
  gl_Position = u_view_projection * vec4(v_world_position, 1.0);
#endif
}

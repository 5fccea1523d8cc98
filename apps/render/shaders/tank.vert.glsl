// The tank's wall and floor: ordinary vertex attributes in world coordinates.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;

out vec3 v_world_position;
out vec3 v_normal;
out vec3 v_albedo;

void main() {
  v_world_position = a_position;
  v_normal = a_normal;
  v_albedo = a_albedo;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}

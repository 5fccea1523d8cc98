// The tank's wall and floor, each vertex its albedo (after surface_inputs.glsl).
in vec3 v_albedo;

void main() { o_colour = vec4(shade(v_albedo, v_world_position, v_normal, v_view_origin), 1.0); }

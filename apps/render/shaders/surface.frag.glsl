// Every lit surface (fish and tank): linear RGB into the floating-point framebuffer.
in vec3 v_world_position;
#ifdef FINFLEX_REFRACTION
in vec3 v_view_origin;  // where the seen ray starts towards the point
#else
#define v_view_origin u_camera_position.xyz
#endif
in vec3 v_normal;
in vec3 v_albedo;

out vec4 o_colour;

void main() { o_colour = vec4(shade(v_albedo, v_world_position, v_normal, v_view_origin), 1.0); }

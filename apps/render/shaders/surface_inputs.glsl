// What every lit surface's fragment shader (surface.frag.glsl, fish.frag.glsl) takes
// from its vertex shader, and gives: linear RGB into the floating-point framebuffer.
in vec3 v_world_position;
#ifdef FINFLEX_REFRACTION
in vec3 v_view_origin;  // where the seen ray starts towards the point
#else
#define v_view_origin u_camera_position.xyz
#endif
in vec3 v_normal;

out vec4 o_colour;

// One vertex of one fish instance, fetched from the caller's buffers by gl_VertexID
// (the index value) and gl_InstanceID: no per-vertex attributes. A stream's element
// (instance i, component c, vertex v), in elements from the start of its buffer
// texture, is
//   s.x + i * s.y + v * s.z + c * s.w,  s = (offset, instance, vertex, component strides)
// (render/fish_draw.hpp; the renderer converts its byte strides), four elements a
// texel where the buffer's range holds whole texels (wide). The instance's
// transform is an instanced attribute (divisor 1), the identity when there is none;
// so is its id (0 when the draw has none): the id pass writes it, the colour pass
// shades each instance by it. A draw from a device list (FishDraw::list) gives the
// instance's entry instead, and the id is the table's.
layout(location = 0) in mat4 a_transform;  // locations 0..3: the matrix's columns
layout(location = 4) in uint a_id;
layout(location = 5) in vec2 a_pattern;  // the vertex's place on the body (Renderer::add_mesh)

uniform samplerBuffer u_positions;  // R32F or R16F; RGBA32F or RGBA16F when wide
uniform samplerBuffer u_normals;
uniform ivec4 u_position_stream;
uniform ivec4 u_normal_stream;
uniform bool u_positions_wide;  // four elements a texel: four times the elements a range
uniform bool u_normals_wide;
uniform usamplerBuffer u_id_table;  // R32UI: FishDraw::ids, with a device list
uniform bool u_ids_from_table;

out vec3 v_world_position;
#ifdef FINFLEX_REFRACTION
out vec3 v_view_origin;  // refraction.glsl apparent_position
#endif
out vec3 v_normal;
out vec2 v_pattern;
flat out uint v_id;

float element(samplerBuffer data, bool wide, int e) {
  return wide ? texelFetch(data, e >> 2)[e & 3] : texelFetch(data, e).r;
}

vec3 fetch(samplerBuffer data, bool wide, ivec4 s, int instance, int vertex) {
  int first = s.x + instance * s.y + vertex * s.z;
  return vec3(element(data, wide, first), element(data, wide, first + s.w),
              element(data, wide, first + 2 * s.w));
}

void main() {
  vec3 position = fetch(u_positions, u_positions_wide, u_position_stream, gl_InstanceID, gl_VertexID);
  vec3 normal = fetch(u_normals, u_normals_wide, u_normal_stream, gl_InstanceID, gl_VertexID);
  vec4 world = a_transform * vec4(position, 1.0);
  v_world_position = world.xyz;
  v_normal = mat3(a_transform) * normal;  // rotation and uniform scale: normalised when shading
  v_pattern = a_pattern;
  v_id = u_ids_from_table ? texelFetch(u_id_table, int(a_id)).r : a_id;
#ifdef FINFLEX_REFRACTION
  gl_Position = u_view_projection * vec4(apparent_position(world.xyz, v_view_origin), 1.0);
#else
  gl_Position = u_view_projection * world;
#endif
}

// One vertex of one fish instance, fetched from the caller's buffers by gl_VertexID
// (the index value) and gl_InstanceID: no per-vertex attributes. A stream's element
// (instance i, component c, vertex v), in elements from the start of its buffer
// texture, is
//   s.x + i * s.y + v * s.z + c * s.w,  s = (offset, instance, vertex, component strides)
// (render/fish_draw.hpp; the renderer converts its byte strides). The instance's
// transform is an instanced attribute (divisor 1), the identity when there is none;
// so is its id, which only the id pass reads (0 otherwise).
layout(location = 0) in mat4 a_transform;  // locations 0..3: the matrix's columns
layout(location = 4) in uint a_id;

uniform samplerBuffer u_positions;  // R32F, or R16F
uniform samplerBuffer u_normals;
uniform ivec4 u_position_stream;
uniform ivec4 u_normal_stream;
uniform vec3 u_albedo;

out vec3 v_world_position;
out vec3 v_normal;
out vec3 v_albedo;
flat out uint v_id;

vec3 fetch(samplerBuffer data, ivec4 s, int instance, int vertex) {
  int first = s.x + instance * s.y + vertex * s.z;
  return vec3(texelFetch(data, first).r, texelFetch(data, first + s.w).r,
              texelFetch(data, first + 2 * s.w).r);
}

void main() {
  vec3 position = fetch(u_positions, u_position_stream, gl_InstanceID, gl_VertexID);
  vec3 normal = fetch(u_normals, u_normal_stream, gl_InstanceID, gl_VertexID);
  vec4 world = a_transform * vec4(position, 1.0);
  v_world_position = world.xyz;
  v_normal = mat3(a_transform) * normal;  // rotation and uniform scale: normalised when shading
  v_albedo = u_albedo;
  v_id = a_id;
  gl_Position = u_view_projection * world;
}

// One vertex of one fish instance, fetched from the caller's buffers by gl_VertexID
// (the index value) and gl_InstanceID: no vertex attributes. A stream's element
// (instance i, component c, vertex v), in elements from the start of its buffer
// texture, is
//   s.x + i * s.y + v * s.z + c * s.w,  s = (offset, instance, vertex, component strides)
// (render/fish_draw.hpp; the renderer converts its byte strides).
uniform samplerBuffer u_positions;   // R32F, or R16F
uniform samplerBuffer u_normals;
uniform samplerBuffer u_transforms;  // RGBA32F: 4 texels (matrix columns) per instance
uniform ivec4 u_position_stream;
uniform ivec4 u_normal_stream;
uniform int u_first_transform;  // index of this draw's first instance in u_transforms
uniform bool u_has_transforms;
uniform vec3 u_albedo;

out vec3 v_world_position;
out vec3 v_normal;
out vec3 v_albedo;

vec3 fetch(samplerBuffer data, ivec4 s, int instance, int vertex) {
  int first = s.x + instance * s.y + vertex * s.z;
  return vec3(texelFetch(data, first).r, texelFetch(data, first + s.w).r,
              texelFetch(data, first + 2 * s.w).r);
}

mat4 instance_transform(int instance) {
  if (!u_has_transforms) return mat4(1.0);
  int first = 4 * (u_first_transform + instance);
  return mat4(texelFetch(u_transforms, first), texelFetch(u_transforms, first + 1),
              texelFetch(u_transforms, first + 2), texelFetch(u_transforms, first + 3));
}

void main() {
  vec3 position = fetch(u_positions, u_position_stream, gl_InstanceID, gl_VertexID);
  vec3 normal = fetch(u_normals, u_normal_stream, gl_InstanceID, gl_VertexID);
  mat4 model = instance_transform(gl_InstanceID);
  vec4 world = model * vec4(position, 1.0);
  v_world_position = world.xyz;
  v_normal = mat3(model) * normal;  // rotation and uniform scale: normalised when shading
  v_albedo = u_albedo;
  gl_Position = u_view_projection * world;
}

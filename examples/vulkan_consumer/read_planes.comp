#version 450
// Reads FinFlex's planes of positions (finflex/batch.hpp: per instance three planes of
// plane_stride floats, vertices at their slots) straight from the memory OpenCL
// wrote, and writes each instance's vertices in the mesh's order as x y z.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Planes { float planes[]; };
layout(std430, binding = 1) readonly buffer Slots { uint slot_of_vertex[]; };
layout(std430, binding = 2) writeonly buffer Vertices { float vertices[]; };

layout(push_constant) uniform Shape {
  uint plane_stride;
  uint vertex_count;
  uint instance_count;
} shape;

void main() {
  uint v = gl_GlobalInvocationID.x;
  uint i = gl_GlobalInvocationID.y;
  if (v >= shape.vertex_count || i >= shape.instance_count) return;
  uint slot = slot_of_vertex[v];
  for (uint c = 0u; c < 3u; ++c) {
    vertices[(i * shape.vertex_count + v) * 3u + c] =
        planes[(3u * i + c) * shape.plane_stride + slot];
  }
}

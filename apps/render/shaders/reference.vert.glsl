// The reference draw's vertex: the deformed position as three plain vertex attributes
// (one float each, from the fish's own buffer), no normal, no transform, no shading:
// what drawing the same triangles costs the GPU's geometry pipeline.
layout(location = 0) in float a_x;
layout(location = 1) in float a_y;
layout(location = 2) in float a_z;

void main() { gl_Position = u_view_projection * vec4(a_x, a_y, a_z, 1.0); }

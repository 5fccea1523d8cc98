// The output transform, applied once: linear RGB (the resolved frame) to sRGB-encoded
// 8-bit values (the IEC 61966-2-1 curve), into a plain RGBA8 framebuffer (no
// GL_FRAMEBUFFER_SRGB, so nothing encodes twice). Rows are written upside down, so
// that glReadPixels, which returns the bottom row first, gives rows from the top.
uniform sampler2D u_linear;

out vec4 o_colour;

vec3 srgb_encode(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
  ivec2 size = textureSize(u_linear, 0);
  ivec2 texel = ivec2(int(gl_FragCoord.x), size.y - 1 - int(gl_FragCoord.y));
  o_colour = vec4(srgb_encode(texelFetch(u_linear, texel, 0).rgb), 1.0);
}

// A fish's colour pass: the species' albedo painted by the vertex's place on the body
// (v_pattern, Renderer::add_mesh) and the instance's id, then lit through the water.
// docs/rendering.md "Fish appearance" gives the pattern (after surface_inputs.glsl).
in vec2 v_pattern;  // u: snout 0 .. tail 1; v: belly -1 .. back 1
flat in uint v_id;

uniform vec3 u_albedo;  // the species' colour
uniform bool u_patterned;

// A well-mixed hash of an integer to [0, 1] (two rounds of multiply and xor-shift).
float hash01(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return float(x) / 4294967295.0;
}

vec3 painted_albedo() {
  // Each fish its own shade: brightness within +-12 %, a little warmer or cooler.
  float brightness = 1.0 + 0.24 * (hash01(v_id) - 0.5);
  float warmth = 0.12 * (hash01(v_id ^ 0x9e3779b9u) - 0.5);
  vec3 base = u_albedo * brightness * vec3(1.0 + warmth, 1.0, 1.0 - warmth);
  // Countershading: a dark back over a pale, silvery belly, blended across the flank.
  vec3 back = base * 0.45;
  vec3 belly = mix(base, vec3(0.80), 0.55);
  vec3 albedo = mix(belly, back, smoothstep(-0.35, 0.45, v_pattern.y));
  // The lateral line: a thin darker stripe a little above mid-flank, from behind the
  // head to the root of the tail.
  float along = step(0.22, v_pattern.x) * step(v_pattern.x, 0.85);
  float line = 1.0 - smoothstep(0.015, 0.05, abs(v_pattern.y - 0.08));
  return albedo * (1.0 - 0.35 * along * line);
}

void main() {
  vec3 albedo = u_patterned ? painted_albedo() : u_albedo;
  o_colour = vec4(shade(albedo, v_world_position, v_normal, v_view_origin), 1.0);
}

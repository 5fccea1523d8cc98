// Lighting and water in linear RGB; render/scene.hpp describes the model.

// The length of the segment from the camera to p that lies under the water surface
// (the rest is air, which neither absorbs nor scatters).
float underwater_length(vec3 p) {
  vec3 eye = u_camera_position.xyz;
  float total = length(p - eye);
  float eye_depth = u_fog_colour.w - eye.y;  // > 0: below the surface
  float point_depth = u_fog_colour.w - p.y;
  if (eye_depth >= 0.0 && point_depth >= 0.0) return total;
  if (eye_depth < 0.0 && point_depth < 0.0) return 0.0;
  return total * max(eye_depth, point_depth) / (abs(eye_depth) + abs(point_depth));
}

// The colour reaching the camera from a surface point p with albedo and normal n.
vec3 shade(vec3 albedo, vec3 p, vec3 n) {
  n = normalize(n);
  vec3 l = u_light_direction.xyz;
  vec3 v = normalize(u_camera_position.xyz - p);
  float depth = max(u_fog_colour.w - p.y, 0.0);

  // Light loses to the water on its way down from the surface: the key light along its
  // slanted path, ambient light straight down.
  vec3 key = u_key_colour.rgb * exp(-u_extinction.rgb * depth / max(l.y, 0.2));
  vec3 ambient = mix(u_ground_ambient.rgb, u_sky_ambient.rgb, 0.5 + 0.5 * n.y) *
                 exp(-u_extinction.rgb * depth);

  float lambert = max(dot(n, l), 0.0);
  vec3 h = normalize(l + v);
  float specular = lambert > 0.0 ? u_key_colour.w * pow(max(dot(n, h), 0.0), u_sky_ambient.w) : 0.0;
  vec3 lit = albedo * (ambient + key * lambert) + key * specular;

  // Exponential fog: what is left of the surface's light, plus the water's own colour.
  vec3 transmitted = exp(-u_extinction.rgb * underwater_length(p));
  return lit * transmitted + u_fog_colour.rgb * (1.0 - transmitted);
}

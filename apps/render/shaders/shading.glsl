// Lighting and water in linear RGB; render/scene.hpp describes the model.

// The length of the segment from the camera to p that lies in the water: the
// cylinder of the tank's radius from the floor (y = 0) to the surface, of the tank p
// is in. The rest is air, which neither absorbs nor scatters (a camera above or
// beside the tank).
float underwater_length(vec3 p) {
  vec2 axis = nearest_tank_axis(p);
  vec3 eye = u_camera_position.xyz - vec3(axis.x, 0.0, axis.y);
  vec3 d = p - vec3(axis.x, 0.0, axis.y) - eye;
  float radius = u_extinction.w;
  float surface = u_fog_colour.w;
  // Parameters t in [0, 1] along eye + t d: first the slab 0 <= y <= surface...
  float t0 = 0.0;
  float t1 = 1.0;
  if (abs(d.y) > 1e-6) {
    float a = (0.0 - eye.y) / d.y;
    float b = (surface - eye.y) / d.y;
    t0 = max(t0, min(a, b));
    t1 = min(t1, max(a, b));
  } else if (eye.y < 0.0 || eye.y > surface) {
    return 0.0;
  }
  // ...then inside the wall: |xz(t)|^2 <= radius^2.
  float qa = dot(d.xz, d.xz);
  float qb = 2.0 * dot(eye.xz, d.xz);
  float qc = dot(eye.xz, eye.xz) - radius * radius;
  if (qa > 1e-12) {
    float discriminant = qb * qb - 4.0 * qa * qc;
    if (discriminant < 0.0) return 0.0;
    float root = sqrt(discriminant);
    t0 = max(t0, (-qb - root) / (2.0 * qa));
    t1 = min(t1, (-qb + root) / (2.0 * qa));
  } else if (qc > 0.0) {
    return 0.0;
  }
  return length(d) * max(t1 - t0, 0.0);
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

// Lighting and water in linear RGB; render/scene.hpp and render/water.hpp describe the
// model, docs/rendering.md "Water" its formulas.

const float kPi = 3.14159265;

// Where the segment from the camera to p lies in the water: the cylinder of the tank's
// radius from the floor (y = 0) to the surface, of the tank p is in. Returns the
// parameters (t0, t1) of origin + t (p - origin) where it enters and leaves, t0 >= t1
// when it does not. The rest is air, which neither absorbs nor scatters (a camera above
// or beside the tank).
vec2 water_segment(vec3 p, vec3 origin) {
  vec2 axis = nearest_tank_axis(p);
  vec3 eye = origin - vec3(axis.x, 0.0, axis.y);
  vec3 d = p - vec3(axis.x, 0.0, axis.y) - eye;
  float radius = u_water_attenuation.w;
  float surface = u_ground_ambient.w;
  // First the slab 0 <= y <= surface...
  float t0 = 0.0;
  float t1 = 1.0;
  if (abs(d.y) > 1e-6) {
    float a = (0.0 - eye.y) / d.y;
    float b = (surface - eye.y) / d.y;
    t0 = max(t0, min(a, b));
    t1 = min(t1, max(a, b));
  } else if (eye.y < 0.0 || eye.y > surface) {
    return vec2(1.0, 0.0);
  }
  // ...then inside the wall: |xz(t)|^2 <= radius^2.
  float qa = dot(d.xz, d.xz);
  float qb = 2.0 * dot(eye.xz, d.xz);
  float qc = dot(eye.xz, eye.xz) - radius * radius;
  if (qa > 1e-12) {
    float discriminant = qb * qb - 4.0 * qa * qc;
    if (discriminant < 0.0) return vec2(1.0, 0.0);
    float root = sqrt(discriminant);
    t0 = max(t0, (-qb - root) / (2.0 * qa));
    t1 = min(t1, (-qb + root) / (2.0 * qa));
  } else if (qc > 0.0) {
    return vec2(1.0, 0.0);
  }
  return vec2(t0, t1);
}

// Henyey-Greenstein's phase function per steradian at the cosine of the scattering angle.
float phase(float cos_angle) {
  float g = u_water_scattering.w;
  float denominator = 1.0 + g * g - 2.0 * g * cos_angle;
  return (1.0 - g * g) / (4.0 * kPi * denominator * sqrt(denominator));
}

// The integral of exp(-x s) for s from 0 to length (x of either sign; length at x = 0).
vec3 exponential_integral(vec3 x, float length) {
  vec3 safe = mix(x, vec3(1.0), lessThan(abs(x), vec3(1e-5)));
  return mix((1.0 - exp(-safe * length)) / safe, vec3(length), lessThan(abs(x), vec3(1e-5)));
}

// The colour reaching the camera from a surface point p with albedo and normal n:
// the surface's light attenuated along the view ray's water, plus the light the
// water scatters into the ray on the way (single scattering). The ray reaches p in a
// straight line from `origin`: the camera, or where it refracted at the surface.
vec3 shade(vec3 albedo, vec3 p, vec3 n, vec3 origin) {
  n = normalize(n);
  vec3 l = u_light_direction.xyz;
  vec3 v = normalize(origin - p);
  float surface = u_ground_ambient.w;
  float depth = max(surface - p.y, 0.0);

  // Light reaching depth z from above falls off as exp(-K_d z) (Kirk).
  vec3 key = u_key_colour.rgb * exp(-u_key_downwelling.rgb * depth);
  vec3 sky = u_sky_ambient.rgb;
  vec3 ambient = mix(u_ground_ambient.rgb, sky, 0.5 + 0.5 * n.y) *
                 exp(-u_ambient_downwelling.rgb * depth);

  float lambert = max(dot(n, l), 0.0);
  vec3 h = normalize(l + v);
  float specular = lambert > 0.0 ? u_key_colour.w * pow(max(dot(n, h), 0.0), u_sky_ambient.w) : 0.0;
  vec3 lit = albedo * (ambient + key * lambert) + key * specular;

  vec2 t = water_segment(p, origin);
  if (t.x >= t.y) return lit;
  vec3 ray = p - origin;
  float in_water = length(ray) * (t.y - t.x);
  vec3 direction = normalize(ray);  // from the camera
  vec3 c = u_water_attenuation.rgb;
  // Depth where the ray enters the water (its camera end) and its rate of change per
  // metre along the ray towards p.
  float entry_depth = max(surface - (origin.y + t.x * ray.y), 0.0);
  float descent = -direction.y;
  // Per metre of the ray, the water scatters towards the camera b p(angle) of the key
  // light's irradiance (pi times key_colour, the radiance of a white surface facing it)
  // and about half of the sky's radiance; both fall off with depth as above, and what
  // is scattered at s metres into the water arrives attenuated by exp(-c s).
  vec3 b = u_water_scattering.rgb;
  vec3 key_source = b * kPi * phase(dot(u_key_in_water.xyz, direction)) * u_key_colour.rgb;
  vec3 sky_source = b * 0.5 * sky;
  vec3 k_key = u_key_downwelling.rgb;
  vec3 k_sky = u_ambient_downwelling.rgb;
  vec3 veil = key_source * exp(-k_key * entry_depth) *
                  exponential_integral(c + k_key * descent, in_water) +
              sky_source * exp(-k_sky * entry_depth) *
                  exponential_integral(c + k_sky * descent, in_water);
  return lit * exp(-c * in_water) + veil;
}

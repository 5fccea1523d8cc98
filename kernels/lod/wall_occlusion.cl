/* Occlusion by tank walls: the float twin of wall_hides_sphere
 * (engine/include/finflex/wall_occlusion.hpp has the geometry, engine/src/lod/
 * wall_occlusion.cpp the double-precision original, step for step). A wall is two
 * float4: (base x, y, z, height) and (outer radius, inner radius: the circle inscribed
 * in its faces, 0, 0). No trigonometry: the wedge's angles by their cosines and sines. */

/* From an eye at distance m from the axis, along a horizontal direction at angle phi
 * from the direction to it (its cosine and sine): where it leaves the circle of radius r. */
inline float wall_exit_distance(const float m, const float cos_phi, const float sin_phi,
                                const float r) {
  const float across = m * sin_phi;
  return m * cos_phi + sqrt(fmax(0.0f, r * r - across * across));
}

/* The wall (shape, radii) against the sphere (centre, radius) seen from the eye, the
 * sphere's horizontal distance d (> radius) and direction u from the eye given. */
inline bool wall_hides(const float3 eye, const float3 centre, const float radius, const float d,
                       const float2 u, const float4 shape, const float4 radii) {
  const float outer = radii.x, inner = radii.y;
  const float2 to_axis = (float2)(shape.x - eye.x, shape.z - eye.z);
  const float along = dot(u, to_axis);
  const float across = fabs(u.x * to_axis.y - u.y * to_axis.x);
  const float m_squared = dot(to_axis, to_axis);
  const bool outside = m_squared >= inner * inner;
  if (outside && (along <= 0.0f || across >= inner)) return false;
  if (!(along + sqrt(fmax(0.0f, outer * outer - across * across)) < d - radius)) return false;
  const float m = sqrt(m_squared);
  const float sin_a = radius / d, cos_a = sqrt(1.0f - sin_a * sin_a);
  const float cos_b = m > 0.0f ? along / m : 1.0f, sin_b = m > 0.0f ? across / m : 0.0f;
  float cos_wide = cos_b * cos_a - sin_b * sin_a, sin_wide = sin_b * cos_a + cos_b * sin_a;
  if (sin_wide < 0.0f || (sin_wide == 0.0f && cos_wide < 0.0f)) {
    cos_wide = -1.0f;
    sin_wide = 0.0f;
  }
  float cos_narrow = cos_b * cos_a + sin_b * sin_a, sin_narrow = sin_b * cos_a - cos_b * sin_a;
  if (sin_narrow < 0.0f) {
    cos_narrow = 1.0f;
    sin_narrow = 0.0f;
  }
  if (outside && !(cos_wide > 0.0f && m * sin_wide < inner)) return false;
  const float nearest_exit = wall_exit_distance(m, cos_wide, sin_wide, inner);
  const float farthest_exit = wall_exit_distance(m, cos_narrow, sin_narrow, outer);
  if (!(farthest_exit < d - radius)) return false;
  const float eye_height = eye.y - shape.y;
  const float low = centre.y - shape.y - radius, high = centre.y - shape.y + radius;
  const float near_share = nearest_exit / (d + radius), far_share = farthest_exit / (d - radius);
  const float h0 = eye_height + (low - eye_height) * near_share;
  const float h1 = eye_height + (low - eye_height) * far_share;
  const float h2 = eye_height + (high - eye_height) * near_share;
  const float h3 = eye_height + (high - eye_height) * far_share;
  return h0 >= 0.0f && h1 >= 0.0f && h2 >= 0.0f && h3 >= 0.0f && h0 <= shape.w && h1 <= shape.w &&
         h2 <= shape.w && h3 <= shape.w;
}

/* Whether any of the `count` walls hides the sphere from the eye. */
inline bool walls_hide(const float3 eye, const float3 centre, const float radius,
                       __global const float4* restrict walls, const uint count) {
  if (count == 0) return false;
  const float2 to_sphere = (float2)(centre.x - eye.x, centre.z - eye.z);
  const float d = length(to_sphere);
  if (!(d > radius)) return false;
  const float2 u = to_sphere / d;
  for (uint w = 0; w < count; ++w) {
    if (wall_hides(eye, centre, radius, d, u, walls[2 * w], walls[2 * w + 1])) return true;
  }
  return false;
}

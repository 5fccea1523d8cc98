// The view rays bending at the flat water surface (render/refraction.hpp, whose
// double-precision functions are the oracle of these): per vertex, where the camera
// sees it. Only in the programs made with FINFLEX_REFRACTION defined
// (Scene::view_refraction; shader_program.hpp refraction_defines).
#ifdef FINFLEX_REFRACTION

// The point q of the surface's plane through which the camera sees p (under the
// surface, the camera above it): Snell's law x / sqrt(x^2 + h^2) =
// n (r - x) / sqrt((r - x)^2 + d^2) for x, q's distance from the camera's foot towards
// p, by Newton's method from the small-angle root (six steps reach float precision).
bool refraction_point(vec3 p, out vec3 q) {
  float n = u_key_in_water.w;
  float surface = u_ground_ambient.w;
  vec3 eye = u_camera_position.xyz;
  if (eye.y <= surface || p.y >= surface) return false;
  float h = eye.y - surface;
  float d = surface - p.y;
  vec2 across = p.xz - eye.xz;
  float r = length(across);
  float x = 0.0;
  if (r > 1e-7) {
    x = n * r * h / (d + n * h);
    for (int i = 0; i < 6; ++i) {
      float a = sqrt(x * x + h * h);
      float b = sqrt((r - x) * (r - x) + d * d);
      float f = x * b - n * (r - x) * a;
      float slope = b - x * (r - x) / b + n * a - n * (r - x) * x / a;
      x = clamp(x - f / slope, 0.0, r);
    }
    q = vec3(eye.x + across.x * x / r, surface, eye.z + across.y * x / r);
  } else {
    q = vec3(eye.x, surface, eye.z);
  }
  return true;
}

// Where the camera sees p: on its ray through q at p's own depth along the camera's
// axis (the depth buffer keeps p's true depth); p itself where nothing refracts.
// `origin`: where the seen ray starts in a straight line towards p (q, else the eye).
vec3 apparent_position(vec3 p, out vec3 origin) {
  vec3 eye = u_camera_position.xyz;
  vec3 q;
  if (!refraction_point(p, q)) {
    origin = eye;
    return p;
  }
  origin = q;
  vec3 forward = u_camera_forward.xyz;
  return eye + (dot(p - eye, forward) / dot(q - eye, forward)) * (q - eye);
}
#endif

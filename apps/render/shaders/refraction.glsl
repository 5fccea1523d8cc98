// The view rays bending at the flat surface or the camera housing's flat port
// (render/refraction.hpp states the equation; its double-precision functions are the
// oracle of these): per vertex, where the camera sees it. Only in the programs made with
// FINFLEX_REFRACTION defined (Scene::view_refraction; shader_program.hpp
// refraction_defines).
#ifdef FINFLEX_REFRACTION

// The lateral run per unit of depth of a ray of sine s (in air) in a medium of index m.
float run(float s, float m) {
  float q = s / m;
  return q * inversesqrt(1.0 - q * q);
}

// The bent ray to p: `entry` on the interface's near face, `exit` on its far face.
// x + t T(s, n_w) + d T(s, n) = r for x, the ray's lateral offset at the near face, by
// Newton's method from the small-angle root (at the port eight steps reach float
// precision to grazing rays; at the surface six).
bool refracted_ray(vec3 p, out vec3 entry, out vec3 exit) {
  float n = u_key_in_water.w;
  vec3 eye = u_camera_position.xyz;
  vec3 normal = vec3(0.0, 1.0, 0.0);
  float h = eye.y - u_ground_ambient.w;  // above the surface
  float t = 0.0;
  float window = 1.0;
  if (u_refraction.x > 1.5) {  // the port, square to the camera's axis
    normal = -u_camera_forward.xyz;
    h = u_refraction.y;
    t = u_refraction.z;
    window = u_refraction.w;
  }
  vec3 v = p - eye;
  float along = -dot(v, normal);
  float d = along - h - t;
  if (h <= 0.0 || d <= 0.0) return false;
  vec3 lateral = v + along * normal;
  float r = length(lateral);
  float x = 0.0;
  float s = 0.0;
  vec3 side = vec3(0.0);
  if (r > 1e-7) {
    x = r * h / (h + t / window + d / n);
    // Uniform per draw: the surface has no window, and converges in fewer steps.
    bool has_window = t > 0.0;
    int steps = u_refraction.x > 1.5 ? 8 : 6;
    for (int i = 0; i < steps; ++i) {
      float inverse_a = inversesqrt(x * x + h * h);
      s = x * inverse_a;
      // f = x + t T(s, n_w) + d T(s, n) - r and its slope in x (dT/ds = 1 / (m c^1.5),
      // c = 1 - (s/m)^2; ds/dx = h^2 / a^3).
      float q = s / n;
      float root = inversesqrt(1.0 - q * q);
      float f = x + d * q * root - r;
      float slope_s = d / n * root * root * root;
      if (has_window) {
        float qw = s / window;
        float root_w = inversesqrt(1.0 - qw * qw);
        f += t * qw * root_w;
        slope_s += t / window * root_w * root_w * root_w;
      }
      float slope = 1.0 + slope_s * h * h * inverse_a * inverse_a * inverse_a;
      x = clamp(x - f / slope, 0.0, r);
    }
    s = x * inversesqrt(x * x + h * h);
    side = lateral / r;
  }
  entry = eye - h * normal + x * side;
  exit = entry - t * normal + t * run(s, window) * side;
  return true;
}

// Where the camera sees p: on its ray through the entry point at p's own depth along the
// camera's axis (the depth buffer keeps p's true depth); p itself where nothing
// refracts. `origin`: where the seen ray starts in a straight line towards p in the water
// (the exit point, else the eye).
vec3 apparent_position(vec3 p, out vec3 origin) {
  vec3 eye = u_camera_position.xyz;
  vec3 entry;
  if (!refracted_ray(p, entry, origin)) {
    origin = eye;
    return p;
  }
  vec3 forward = u_camera_forward.xyz;
  return eye + (dot(p - eye, forward) / dot(entry - eye, forward)) * (entry - eye);
}
#endif

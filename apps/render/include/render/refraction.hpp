// The view rays bending at a flat interface by Snell's law (Scene::view_refraction):
//  - kSurface: a camera above the water sees through its flat surface;
//  - kPort: a camera in the water sees through its housing's flat window (air inside,
//    the window of thickness t and index n_w, water beyond), square to its axis.
// In both a point beyond the interface is seen along the ray that leaves the camera at
// lateral offset x on the interface's near face, where (h the camera's distance from
// that face, d the point's beyond the far face, r its lateral distance, n the water's
// index, s = x / sqrt(x^2 + h^2) the sine of the ray's angle in air)
//   x + t T(s, n_w) + d T(s, n) = r,   T(s, m) = (s/m) / sqrt(1 - (s/m)^2),
// each term the ray's lateral run in air, window and water (Snell: sin = s/m in each).
// The renderer applies it to every vertex (shaders/refraction.glsl, the same equation
// by Newton's method in single precision) and interpolates within triangles; these
// functions are the double-precision oracle (bisection) that the dataset's keypoints use.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "render/camera.hpp"
#include "render/scene.hpp"

namespace finflex::render {

// The bent view ray to a point: where it meets the interface's near face (the surface,
// the window's inner face) and where it leaves the far face into the water (the same
// point at the surface).
struct RefractedRay {
  glm::dvec3 entry;
  glm::dvec3 exit;
};

// The ray through which `camera` sees `point`, when the scene refracts its view rays,
// the camera is on the interface's near side and the point beyond its far face; nullopt
// otherwise. The surface's plane counts beyond the wall too: a point seen through the
// cut-away's near wall is seen as if through the surface (no jump where the rays leave
// the surface for the wall).
std::optional<RefractedRay> refracted_ray(const Scene& scene, const Camera& camera,
                                          const glm::dvec3& point);

// Where the camera sees `point`: on the ray from the eye through its entry point, at the
// point's own depth along the camera's axis (so the depth buffer holds the true depth);
// the point itself where nothing refracts.
glm::dvec3 apparent_point(const Scene& scene, const Camera& camera, const glm::dvec3& point);

}  // namespace finflex::render

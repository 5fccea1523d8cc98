// The view rays of a camera above the water bending at its flat surface (Snell's law,
// Scene::view_refraction): a point under the surface is seen along the ray from the
// camera to the surface point q where
//   sin(angle in air) = n sin(angle in water),
// both angles from the vertical, the camera, q and the point in one vertical plane.
// The renderer applies it to every vertex (shaders/refraction.glsl, the same solution
// in single precision) and interpolates within triangles; these functions are the
// double-precision oracle that the dataset's keypoints use.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "render/camera.hpp"
#include "render/scene.hpp"

namespace finflex::render {

// The point q of the surface's plane through which a camera at `eye` sees `point`,
// when the scene refracts the view rays, the eye is above the surface and the point
// below it; nullopt otherwise. The plane counts beyond the wall too: a point seen
// through the cut-away's near wall is seen as if through the surface (no jump where
// the rays leave the surface for the wall).
std::optional<glm::dvec3> refraction_point(const Scene& scene, const glm::dvec3& eye,
                                           const glm::dvec3& point);

// Where the camera sees `point`: on the ray from the eye through its refraction point,
// at the point's own depth along the camera's axis (so the depth buffer holds the
// true depth); the point itself where nothing refracts.
glm::dvec3 apparent_point(const Scene& scene, const Camera& camera, const glm::dvec3& point);

}  // namespace finflex::render

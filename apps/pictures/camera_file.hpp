// The camera of a rendered set of frames as a JSON object (camera.json), for tools that
// measure in the images: pinhole intrinsics and the pose, with their conventions
// written out in the file itself.
#pragma once

#include <nlohmann/json.hpp>

#include "lens.hpp"
#include "render/camera.hpp"
#include "render/scene.hpp"

namespace finflex::pictures {

// {"model": "pinhole", "width", "height", "fx", "fy", "cx", "cy", "K" (3x3 rows),
//  "distortion" (k1 k2 p1 p2 k3, OpenCV's order: lens.hpp), "camera_from_world" and
//  "world_from_camera" (4x4 rows, OpenCV axes), "position", "target", "up", "vertical_fov_degrees",
//  "near", "far", "conventions": {...}}. Values from render::pinhole_intrinsics and
//  render::camera_from_world. With `refraction` (a scene whose view rays bend,
//  render::Scene::view_refraction) also "refraction": {"interface": "surface",
//  "surface_y_m", "refractive_index", "tank_radius_m"} or {"interface": "port",
//  "port_distance_m", "port_thickness_m", "port_refractive_index", "refractive_index",
//  "tank_radius_m"}.
nlohmann::ordered_json camera_json(const render::Camera& camera, int width, int height,
                                   const LensDistortion& distortion = {},
                                   const render::Scene* refraction = nullptr);

// The right camera of a rectified stereo pair: `left` moved `baseline` metres along its
// own x axis (OpenCV's: right in the image), the same orientation and intrinsics.
render::Camera stereo_right_camera(const render::Camera& left, double baseline);

// camera_json(left) with "stereo": {"baseline_m", "right" (the right camera's
// camera_json, without conventions), "R" (identity), "T" ([-baseline, 0, 0]: OpenCV's
// stereoCalibrate convention, X_right = R X_left + T), "rectified": true, "P1", "P2",
// "Q" (as cv::stereoRectify gives them for this pair: P2's last column -fx baseline),
// "disparity"}.
nlohmann::ordered_json stereo_camera_json(const render::Camera& left, double baseline, int width,
                                          int height, const LensDistortion& distortion = {},
                                          const render::Scene* refraction = nullptr);

}  // namespace finflex::pictures

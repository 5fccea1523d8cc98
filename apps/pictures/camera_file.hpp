// The camera of a rendered set of frames as a JSON object (camera.json), for tools that
// measure in the images: pinhole intrinsics and the pose, with their conventions
// written out in the file itself.
#pragma once

#include <nlohmann/json.hpp>

#include "render/camera.hpp"

namespace finflex::pictures {

// {"model": "pinhole", "width", "height", "fx", "fy", "cx", "cy", "K" (3x3 rows),
//  "distortion" (zeros: k1 k2 p1 p2 k3), "camera_from_world" and "world_from_camera"
//  (4x4 rows, OpenCV axes), "position", "target", "up", "vertical_fov_degrees",
//  "near", "far", "conventions": {...}}. Values from render::pinhole_intrinsics and
//  render::camera_from_world.
nlohmann::ordered_json camera_json(const render::Camera& camera, int width, int height);

}  // namespace finflex::pictures

#include "camera_file.hpp"

#include <string>

namespace finflex::pictures {

namespace {

nlohmann::ordered_json rows(const glm::dmat4& m) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) out.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return out;
}

nlohmann::ordered_json vector(const glm::vec3& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

// The refraction part of the "optics" convention.
std::string refraction_words(const render::Scene* refraction) {
  const render::ViewRefraction kind =
      refraction ? refraction->view_refraction : render::ViewRefraction::kNone;
  switch (kind) {
    case render::ViewRefraction::kSurface:
      return ", the view rays refracted at the water surface by Snell's law (refraction: the "
             "plane y = surface_y_m)";
    case render::ViewRefraction::kPort:
      return ", the camera in the water behind a flat port, the view rays refracted by Snell's "
             "law from air into the window and from the window into the water (refraction: "
             "the window's faces square to the camera's z axis at Z = port_distance_m and "
             "port_distance_m + port_thickness_m)";
    case render::ViewRefraction::kNone:
      break;
  }
  return ", no refraction";
}

}  // namespace

nlohmann::ordered_json camera_json(const render::Camera& camera, int width, int height,
                                   const LensDistortion& distortion,
                                   const render::Scene* refraction) {
  const render::PinholeIntrinsics k = render::pinhole_intrinsics(camera, width, height);
  const glm::dmat4 camera_from_world = render::camera_from_world(camera);
  nlohmann::ordered_json out;
  out["model"] = "pinhole";
  out["width"] = width;
  out["height"] = height;
  out["fx"] = k.fx;
  out["fy"] = k.fy;
  out["cx"] = k.cx;
  out["cy"] = k.cy;
  out["K"] = {{k.fx, 0.0, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}};
  out["distortion"] = {distortion.k1, distortion.k2, distortion.p1, distortion.p2, distortion.k3};
  out["camera_from_world"] = rows(camera_from_world);
  out["world_from_camera"] = rows(glm::inverse(camera_from_world));
  out["position"] = vector(camera.position);
  out["target"] = vector(camera.target);
  out["up"] = vector(camera.up);
  out["vertical_fov_degrees"] = camera.vertical_fov_degrees;
  out["near"] = camera.near_plane;
  out["far"] = camera.far_plane;
  out["conventions"] = {
      {"world", "metres; y up; the tank's axis is the y axis, its floor the plane y = 0"},
      {"camera", "OpenCV axes: x right, y down, z forward (the view direction)"},
      {"projection",
       "u = fx X / Z + cx, v = fy Y / Z + cy for (X, Y, Z) = camera_from_world (x, y, z, 1)"},
      {"pixels",
       "(u, v) from the image's top-left corner; pixel (i, j) covers [i, i+1) x [j, j+1), "
       "its centre at (i + 0.5, j + 0.5); for tools whose pixel centres are integers, "
       "use cx - 0.5 and cy - 0.5"},
      {"optics", std::string(distortion.none() ? "an ideal pinhole"
                                               : "a pinhole with lens distortion in OpenCV's model "
                                                 "(cv::projectPoints: k1 k2 p1 p2 k3)") +
                     refraction_words(refraction)}};
  if (refraction && refraction->view_refraction == render::ViewRefraction::kSurface) {
    out["refraction"] = {{"interface", "surface"},
                         {"surface_y_m", refraction->tank.water_depth},
                         {"refractive_index", refraction->water.refractive_index},
                         {"tank_radius_m", refraction->tank.radius}};
  } else if (refraction && refraction->view_refraction == render::ViewRefraction::kPort) {
    out["refraction"] = {{"interface", "port"},
                         {"port_distance_m", refraction->port.distance},
                         {"port_thickness_m", refraction->port.thickness},
                         {"port_refractive_index", refraction->port.refractive_index},
                         {"refractive_index", refraction->water.refractive_index},
                         {"tank_radius_m", refraction->tank.radius}};
  }
  return out;
}

render::Camera stereo_right_camera(const render::Camera& left, double baseline) {
  const glm::dmat4 camera_from_world = render::camera_from_world(left);
  // Row 0 of the rotation: the camera's x axis in world coordinates.
  const glm::dvec3 x_axis(camera_from_world[0][0], camera_from_world[1][0],
                          camera_from_world[2][0]);
  render::Camera right = left;
  right.position = glm::vec3(glm::dvec3(left.position) + baseline * x_axis);
  right.target = glm::vec3(glm::dvec3(left.target) + baseline * x_axis);
  return right;
}

nlohmann::ordered_json stereo_camera_json(const render::Camera& left, double baseline, int width,
                                          int height, const LensDistortion& distortion,
                                          const render::Scene* refraction) {
  nlohmann::ordered_json out = camera_json(left, width, height, distortion, refraction);
  nlohmann::ordered_json right =
      camera_json(stereo_right_camera(left, baseline), width, height, distortion);
  right.erase("conventions");
  const render::PinholeIntrinsics k = render::pinhole_intrinsics(left, width, height);
  nlohmann::ordered_json stereo;
  stereo["baseline_m"] = baseline;
  stereo["right"] = right;
  stereo["R"] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  stereo["T"] = {-baseline, 0.0, 0.0};
  stereo["rectified"] = true;
  stereo["P1"] = {{k.fx, 0.0, k.cx, 0.0}, {0.0, k.fy, k.cy, 0.0}, {0.0, 0.0, 1.0, 0.0}};
  stereo["P2"] = {
      {k.fx, 0.0, k.cx, -k.fx * baseline}, {0.0, k.fy, k.cy, 0.0}, {0.0, 0.0, 1.0, 0.0}};
  stereo["Q"] = {{1.0, 0.0, 0.0, -k.cx},
                 {0.0, 1.0, 0.0, -k.cy},
                 {0.0, 0.0, 0.0, k.fx},
                 {0.0, 0.0, 1.0 / baseline, 0.0}};
  stereo["disparity"] =
      "d = u_left - u_right = fx baseline_m / Z (Z the left camera's depth); the same row v";
  out["stereo"] = stereo;
  return out;
}

}  // namespace finflex::pictures

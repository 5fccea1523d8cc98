#include "render/camera.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "checks.hpp"

namespace finflex::render {

void Camera::validate() const {
  detail::require_finite("camera.position", position);
  detail::require_finite("camera.target", target);
  detail::require_finite("camera.up", up);
  const glm::vec3 view = target - position;
  if (glm::length(view) <= 0.0f) {
    detail::invalid("camera.target", detail::to_text(target) + " is the camera's position");
  }
  if (glm::length(up) <= 0.0f) detail::invalid("camera.up", "is zero");
  const float sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(up)));
  if (sine < 1e-4f) {
    detail::invalid("camera.up", detail::to_text(up) + " is parallel to the view direction");
  }
  detail::require_finite("camera.vertical_fov_degrees", vertical_fov_degrees);
  if (!(vertical_fov_degrees > 0.0f && vertical_fov_degrees < 180.0f)) {
    detail::invalid("camera.vertical_fov_degrees",
                    detail::to_text(vertical_fov_degrees) + " is outside (0, 180)");
  }
  detail::require_positive("camera.near_plane", near_plane);
  detail::require_finite("camera.far_plane", far_plane);
  if (!(far_plane > near_plane)) {
    detail::invalid("camera.far_plane", detail::to_text(far_plane) + " is not > near_plane " +
                                            detail::to_text(near_plane));
  }
}

glm::mat4 view_matrix(const Camera& camera) {
  return glm::lookAt(camera.position, camera.target, camera.up);
}

glm::mat4 projection_matrix(const Camera& camera, float aspect) {
  return glm::perspective(glm::radians(camera.vertical_fov_degrees), aspect, camera.near_plane,
                          camera.far_plane);
}

glm::vec3 project_to_pixel(const Camera& camera, int width, int height, const glm::vec3& world) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::vec4 clip =
      projection_matrix(camera, aspect) * view_matrix(camera) * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(width),
          (0.5f - ndc.y * 0.5f) * static_cast<float>(height), clip.w};
}

PinholeIntrinsics pinhole_intrinsics(const Camera& camera, int width, int height) {
  const double half_angle = glm::radians(static_cast<double>(camera.vertical_fov_degrees)) / 2.0;
  PinholeIntrinsics k;
  k.fy = 0.5 * static_cast<double>(height) / std::tan(half_angle);
  k.fx = k.fy;
  k.cx = 0.5 * static_cast<double>(width);
  k.cy = 0.5 * static_cast<double>(height);
  return k;
}

glm::dmat4 camera_from_world(const Camera& camera) {
  const glm::dmat4 view =
      glm::lookAt(glm::dvec3(camera.position), glm::dvec3(camera.target), glm::dvec3(camera.up));
  const glm::dmat4 flip = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -1.0, -1.0));
  return flip * view;
}

}  // namespace finflex::render

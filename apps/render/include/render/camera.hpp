// The camera: a look-at perspective view. World units are metres, y is up; the
// tank stands on y = 0 (render/scene.hpp).
#pragma once

#include <glm/glm.hpp>

namespace finflex::render {

struct Camera {
  glm::vec3 position{0.0f, 2.6f, 2.4f};  // the eye, in world metres
  glm::vec3 target{0.0f, 0.3f, 0.0f};    // the point looked at (centre of the image)
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // roughly up in the image; not parallel to the view
  float vertical_fov_degrees = 45.0f;    // the image's full vertical angle, in (0, 180)
  float near_plane = 0.05f;              // clip distances along the view, 0 < near < far
  float far_plane = 50.0f;

  // Throws RenderError (kInvalidArgument) naming the field ("camera.up", ...) when a
  // value is not finite, the target is the position, up is zero or parallel to the
  // view direction, the field of view is out of (0, 180) or the planes are not
  // 0 < near < far.
  void validate() const;
};

// World to eye (right-handed, looking down -z), as gluLookAt.
glm::mat4 view_matrix(const Camera& camera);
// Eye to clip, as gluPerspective; aspect = width / height.
glm::mat4 projection_matrix(const Camera& camera, float aspect);
// Where a world point lands in an image of width x height pixels: x right, y down,
// from the top-left corner (rows as Image stores them); z is the clip-space w (> 0
// in front of the camera).
glm::vec3 project_to_pixel(const Camera& camera, int width, int height, const glm::vec3& world);

// The same projection as a pinhole camera, for tools that calibrate with one (OpenCV,
// COLMAP, a dataset's camera file). Camera coordinates on OpenCV's axes (x right, y
// down, z forward, metres); a point (X, Y, Z) with Z > 0 lands at
//   u = fx X / Z + cx,   v = fy Y / Z + cy
// in pixels from the image's top-left corner, as project_to_pixel: pixel (i, j)
// covers [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5). Square pixels:
// fx = fy = (height / 2) / tan(vertical_fov / 2); cx = width / 2, cy = height / 2.
// (Tools whose pixel centres are the integers use cx - 0.5 and cy - 0.5.)
struct PinholeIntrinsics {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
};
PinholeIntrinsics pinhole_intrinsics(const Camera& camera, int width, int height);

// World (metres, y up) to camera coordinates on OpenCV's axes: the view matrix with
// its y and z axes turned around (diag(1, -1, -1) view_matrix(camera)); a rigid motion.
glm::dmat4 camera_from_world(const Camera& camera);

}  // namespace finflex::render

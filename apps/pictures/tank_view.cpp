#include "tank_view.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::pictures {

namespace {

constexpr float kVerticalFovDegrees = 40.0f;
constexpr float kMargin = 1.06f;  // room around the tank in the frame

// tan of half the narrower field of view (vertical, or horizontal in a portrait image).
float half_view_tangent(int width, int height) {
  const float vertical = std::tan(0.5f * glm::radians(kVerticalFovDegrees));
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  return vertical * std::min(aspect, 1.0f);
}

// The tank's outline as the camera sees it: points on the rim's and the floor's circles.
std::vector<glm::vec3> tank_outline(float radius, float rim) {
  std::vector<glm::vec3> points;
  for (int k = 0; k < 64; ++k) {
    const float angle = 6.2831853f * static_cast<float>(k) / 64.0f;
    const glm::vec2 around = radius * glm::vec2(std::cos(angle), std::sin(angle));
    points.emplace_back(around.x, rim, around.y);
    points.emplace_back(around.x, 0.0f, around.y);
  }
  return points;
}

// From the tank's +z side, `down` radians below the horizontal, at the distance and
// height where `outline` just fills the frame (its projection centred vertically,
// kMargin to spare): fixed-point steps, each scaling the distance by the outline's
// extent and moving the point looked at up or down to centre it.
render::Camera fit_view(render::Camera camera, float down, const std::vector<glm::vec3>& outline,
                        glm::vec3 target, int width, int height) {
  const glm::vec3 back{0.0f, std::sin(down), std::cos(down)};  // from the target to the eye
  const float tangent = std::tan(0.5f * glm::radians(camera.vertical_fov_degrees));
  float distance = 0.0f;
  for (const glm::vec3& p : outline) distance = std::max(distance, 3.0f * glm::length(p - target));
  for (int step = 0; step < 16; ++step) {
    camera.target = target;
    camera.position = target + distance * back;
    glm::vec2 low(1e9f), high(-1e9f);
    for (const glm::vec3& p : outline) {
      const glm::vec3 pixel = render::project_to_pixel(camera, width, height, p);
      const glm::vec2 ndc(2.0f * pixel.x / static_cast<float>(width) - 1.0f,
                          1.0f - 2.0f * pixel.y / static_cast<float>(height));
      low = glm::min(low, ndc);
      high = glm::max(high, ndc);
    }
    const float extent = std::max(high.x - low.x, high.y - low.y) * 0.5f;
    // An image offset of c (NDC, vertical) is about c d tan / cos(down) along y.
    target.y += 0.5f * (low.y + high.y) * distance * tangent / std::cos(down);
    distance *= extent * kMargin;
  }
  camera.target = target;
  camera.position = target + distance * back;
  return camera;
}

}  // namespace

const char* to_string(CameraView view) {
  switch (view) {
    case CameraView::kAbove:
      return "above";
    case CameraView::kSide:
      return "side";
    case CameraView::kUnderwater:
      return "underwater";
    case CameraView::kOblique:
      break;
  }
  return "oblique";
}

CameraView parse_camera_view(const std::string& text, const std::string& option) {
  for (CameraView view :
       {CameraView::kAbove, CameraView::kOblique, CameraView::kSide, CameraView::kUnderwater}) {
    if (text == to_string(view)) return view;
  }
  throw Error(ErrorCode::kInvalidArgument, option,
              option + " '" + text + "' is not a camera view (above, oblique, side or underwater)");
}

render::Scene tank_scene(const tank::HallSettings& settings) {
  render::Scene scene;
  const auto depth = static_cast<float>(settings.tank.depth);
  scene.tank.radius = static_cast<float>(0.5 * settings.tank.diameter);
  scene.tank.water_depth = depth;
  scene.tank.wall_height = static_cast<float>(settings.tank.wall_height());
  scene.tank.segments = settings.tank.wall_faces;
  scene.rows.count = static_cast<int>(settings.tanks);
  scene.rows.columns = static_cast<int>(settings.columns);
  scene.rows.spacing = static_cast<float>(settings.tank.diameter + settings.walkway);
  return scene;
}

render::Camera tank_camera(const tank::TankSettings& settings, CameraView view, int width,
                           int height) {
  const auto radius = static_cast<float>(0.5 * settings.diameter);
  const auto depth = static_cast<float>(settings.depth);
  const auto rim = static_cast<float>(settings.wall_height());
  const float tangent = half_view_tangent(width, height);
  render::Camera camera;
  camera.vertical_fov_degrees = kVerticalFovDegrees;
  camera.far_plane = 10.0f * (radius + depth) + 10.0f;
  switch (view) {
    case CameraView::kAbove: {
      // The rim's circle (the widest thing nearest the camera) fills the narrower
      // half-field: its distance below the camera is radius / tan.
      camera.position = {0.0f, rim + kMargin * radius / tangent, 0.0f};
      camera.target = {0.0f, 0.0f, 0.0f};
      camera.up = {0.0f, 0.0f, -1.0f};
      break;
    }
    case CameraView::kSide: {
      // Level with the middle of the water, outside the near wall (not drawn): the
      // tank's widest section, across its axis, fills the frame's width, and the
      // near wall's rim stays above the frame's top edge.
      const float aspect = static_cast<float>(width) / static_cast<float>(height);
      const float vertical = std::tan(0.5f * glm::radians(kVerticalFovDegrees));
      const float from_axis = std::max(kMargin * radius / (vertical * aspect),
                                       kMargin * (rim - 0.5f * depth) / vertical + radius);
      camera.position = {0.0f, 0.5f * depth, from_axis};
      camera.target = {0.0f, 0.5f * depth, 0.0f};
      break;
    }
    case CameraView::kUnderwater:
      // 5 % of the radius in from the wall (a housing on it), looking at the axis at a
      // tenth of the depth: about 12 degrees down for the default tank, so the frame's
      // top edge meets the far wall below the surface (which is not drawn from below).
      camera.position = {0.0f, 0.4f * depth, 0.95f * radius};
      camera.target = {0.0f, 0.1f * depth, 0.0f};
      camera.near_plane = 0.03f;  // the housing's port: nothing is seen nearer
      break;
    case CameraView::kOblique:
      camera = fit_view(camera, glm::radians(40.0f), tank_outline(radius, rim),
                        {0.0f, depth / 3.0f, 0.0f}, width, height);
      break;
  }
  return camera;
}

render::Camera hall_view_camera(const tank::HallSettings& settings, CameraView view, int width,
                                int height) {
  if (settings.tanks <= 1) return tank_camera(settings.tank, view, width, height);
  const tank::HallCamera hall = tank::hall_camera(settings);
  render::Camera camera;
  camera.position = glm::vec3(hall.eye);
  camera.target = glm::vec3(hall.target);
  camera.up = glm::vec3(hall.up);
  camera.vertical_fov_degrees = static_cast<float>(hall.vertical_fov_degrees);
  camera.near_plane = static_cast<float>(hall.near_plane);
  camera.far_plane = static_cast<float>(hall.far_plane);
  return camera;
}

glm::vec3 species_albedo(const std::string& species_name, std::size_t index) {
  if (species_name.rfind("blub", 0) == 0) return {0.80f, 0.36f, 0.10f};        // orange
  if (species_name.rfind("barramundi", 0) == 0) return {0.55f, 0.58f, 0.56f};  // silver
  const glm::vec3 palette[] = {
      {0.75f, 0.62f, 0.20f}, {0.30f, 0.45f, 0.70f}, {0.70f, 0.30f, 0.35f}, {0.35f, 0.60f, 0.35f}};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

}  // namespace finflex::pictures

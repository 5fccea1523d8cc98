// How the tank of apps/tank looks to the renderer: its walls and water as a
// render::Scene, the camera views the swim offers, and each species' colour.
#pragma once

#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "hall.hpp"
#include "render/camera.hpp"
#include "render/scene.hpp"
#include "tank.hpp"

namespace finflex::pictures {

// Where the camera stands, each framing the whole tank (metres, y up, the tank's axis
// on y, its floor at y = 0):
//   kAbove:   straight down from above the rim, as the counting cameras of fish farms;
//   kOblique: from above and to one side, 40 degrees down (the default: depth shows);
//   kSide:    level with the middle of the water, through the near wall (drawn cut away),
//             as through a tank window;
//   kUnderwater: in the water at the near wall, 40 % of the depth up, looking across
//             the tank towards its axis low over the floor, as the wall-mounted cameras
//             of RAS monitoring (in a housing whose flat port bends its view rays with
//             Scene::view_refraction kPort).
enum class CameraView { kAbove, kOblique, kSide, kUnderwater };

const char* to_string(CameraView view);
// "above", "oblique", "side", "underwater"; kInvalidArgument naming `option` and the text
// otherwise.
CameraView parse_camera_view(const std::string& text, const std::string& option);

// The tank as the renderer draws it: the settings' diameter and water depth, a wall
// 10 % higher than the water (the freeboard), the default water and light; a hall's
// tanks in its rows.
render::Scene tank_scene(const tank::HallSettings& settings);

// The camera of `view` for an image of width x height pixels: a 40-degree vertical
// field of view (wider when the image is narrower than it is tall), placed so the tank
// fills the frame with a small margin.
render::Camera tank_camera(const tank::TankSettings& settings, CameraView view, int width,
                           int height);
// A hall's camera: tank_camera's for one tank, tank::hall_camera for several (`view`
// then unused).
render::Camera hall_view_camera(const tank::HallSettings& settings, CameraView view, int width,
                                int height);

// A species' colour (linear RGB): Blub orange, the Barramundi silver, others from a
// small palette by `index`.
glm::vec3 species_albedo(const std::string& species_name, std::size_t index);

}  // namespace finflex::pictures

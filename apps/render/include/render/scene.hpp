// What surrounds the fish: a round tank of water, the light, the water's colour.
// Colours are linear RGB (the renderer shades in linear light and encodes sRGB once,
// on output). Lengths are metres; y is up and the tank's floor is the disc y = 0
// around the origin.
#pragma once

#include <glm/glm.hpp>

#include "render/water.hpp"

namespace finflex::render {

// A round RAS tank: a cylindrical wall and a flat floor. The wall is drawn from the
// inside only, so a camera outside or above the tank sees through its near side.
struct Tank {
  float radius = 1.5f;                          // inner radius of the wall
  float wall_height = 1.1f;                     // floor to rim
  float water_depth = 1.0f;                     // floor to water surface, <= wall_height
  glm::vec3 wall_albedo{0.30f, 0.37f, 0.40f};   // grey-blue fibreglass
  glm::vec3 floor_albedo{0.18f, 0.22f, 0.23f};  // darker, with the drain at the centre
  int segments = 96;                            // facets around the wall, >= 8
};

// Tanks of the one kind in rows (a farm hall): tank t's axis at
//   x = (t mod columns) spacing,  z = -floor(t / columns) spacing,
// tank 0's on the y axis. Each fragment is in the water of the tank nearest it.
struct TankRows {
  int count = 1;         // 1 .. 4096
  int columns = 1;       // tanks per row, >= 1
  float spacing = 0.0f;  // m between neighbouring axes: at least the diameter when count > 1
};

// A key light from above (directional) plus hemispheric ambient light: Lambert
// diffuse and a little Blinn-Phong specular.
struct Lighting {
  glm::vec3 direction_to_light{0.25f, 1.0f, 0.15f};  // normalised on use; y > 0: from above
  glm::vec3 key_colour{1.25f, 1.22f, 1.15f};         // irradiance at the surface
  glm::vec3 sky_ambient{0.16f, 0.22f, 0.24f};        // ambient from above (n.y = 1)
  glm::vec3 ground_ambient{0.03f, 0.04f, 0.04f};     // ambient from below (n.y = -1)
  float specular = 0.25f;                            // Blinn-Phong strength, 0..1
  float shininess = 48.0f;                           // Blinn-Phong exponent
};

// Where a camera's view rays bend on their way to what it sees (render/refraction.hpp).
enum class ViewRefraction {
  kNone,     // straight: an ideal cut-away seen from outside, or an ideal pinhole in the water
  kSurface,  // at the water's flat surface, the camera above it
  kPort,     // at the flat port of the camera's housing in the water: air inside, a
             // window of acrylic or glass square to the camera's axis, water beyond
};

const char* to_string(ViewRefraction refraction);  // "none", "surface", "port"

// A camera housing's flat port (ViewRefraction::kPort). Defaults: a 10 mm acrylic window
// (PMMA, n = 1.49 at 589 nm) 20 mm in front of the lens's centre of projection.
struct FlatPort {
  float distance = 0.02f;          // m from the centre of projection to the window's inner face
  float thickness = 0.01f;         // m of window, >= 0
  float refractive_index = 1.49f;  // of the window, 1 .. 2
};

struct Scene {
  Tank tank;
  TankRows rows;
  // Only the part of a view ray inside the water (the tank's cylinder below the
  // surface) absorbs and scatters: a camera above or beside the tank looks through
  // clear air first. In a hall, that is the water of the tank the seen point is in.
  Water water = water_optics(WaterComposition{});
  Lighting lighting;
  // Where the view rays bend by Snell's law (render/refraction.hpp; the water's
  // water.refractive_index), applied per vertex: kSurface for a camera above the water,
  // kPort for one in it behind `port`; kNone: they go straight.
  ViewRefraction view_refraction = ViewRefraction::kNone;
  FlatPort port;
  glm::vec3 background{0.015f, 0.017f, 0.02f};  // outside the tank: a dim room

  // Throws RenderError (kInvalidArgument) naming the field ("scene.tank.radius", ...)
  // when a value is not finite, a length is not > 0, water_depth exceeds wall_height,
  // a colour, absorption or scattering is negative, phase_asymmetry is outside
  // 0 .. 0.99, refractive_index outside 1 .. 2, specular outside 0 .. 1, shininess < 1,
  // segments < 8, direction_to_light is zero, rows ("scene.rows.count", ...) out of
  // its ranges, or the port ("scene.port.distance", ...) has a distance not > 0, a
  // negative thickness or an index outside 1 .. 2.
  void validate() const;
};

}  // namespace finflex::render

// The water and the light of each picture: a water type (or a composition given in
// full) and, for domain randomisation, a fresh draw every frame from documented
// ranges, seeded so that the same run gives the same frames (docs/dataset.md
// "Water and light").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "render/scene.hpp"

namespace finflex::pictures {

// What a frame is drawn with: the water's composition, the lights' strength (times the
// scene's key and ambient lights) and the direction towards the key light (nullopt:
// the scene's).
struct FrameOptics {
  render::WaterComposition water;
  double light_scale = 1.0;
  std::optional<glm::vec3> direction_to_light;
};

// The ranges each varied frame draws from, uniformly (independent draws).
struct OpticsRanges {
  double turbidity_ntu[2] = {0.0, 5.0};
  double dissolved_absorption_440[2] = {0.0, 3.0};  // m^-1
  double light_scale[2] = {0.5, 1.5};
  double light_elevation_degrees[2] = {50.0, 90.0};  // above the horizon; any azimuth
};

struct OpticsSettings {
  FrameOptics base;   // every frame's, unless varied
  bool vary = false;  // each frame its own draw from `ranges`
  std::uint64_t seed = 1;
  OpticsRanges ranges;
};

// The named water types (water_type_names()): kInvalidArgument naming `option` for
// another name.
render::WaterComposition water_type(const std::string& name, const std::string& option);
const char* water_type_names();  // "clear, ras, turbid"

// Frame `frame`'s optics: the base, or with `vary` the frame's draw (the same seed and
// frame give the same draw, whatever else the run does).
FrameOptics frame_optics(const OpticsSettings& settings, std::size_t frame);

// `scene` with the frame's water and light.
render::Scene with_optics(const render::Scene& scene, const FrameOptics& optics);

// For coco.json's images: the composition, the optical properties per channel that
// follow from it, and the light, of `drawn` (with_optics of `optics`).
nlohmann::ordered_json optics_json(const FrameOptics& optics, const render::Scene& drawn);

}  // namespace finflex::pictures

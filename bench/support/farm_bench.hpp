// The farm as `finflex bench --farm` times it: a hall of tanks of swimming fish of one
// species (tank::HallSettings::farm: 16 tanks in rows of 4, the fish spread over them)
// seen by one camera (farm_camera), with levels of detail (tank::SceneLevels: per frame
// the swim drivers, the level choice and each level's deformation of the fish it
// chose) and the same hall at full detail (every fish, every vertex), their frames
// interleaved in one run and timed by profiling events from the driver's start to the
// last deformation's end. The hall's steps are recorded before the timed frames and
// replayed into both (the same fish in both scenes).
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "finflex/finflex.hpp"
#include "hall.hpp"

namespace finflex::bench {

struct FarmSettings {
  std::size_t fish = 100000;
  std::size_t tanks = 16;
  std::size_t frames = 40;
  int width = 1920, height = 1080;
  NormalMode normals = NormalMode::kRotate;
  NormalFormat format = NormalFormat::kFloat32;
  LevelOptions levels;
  LevelChoiceOptions choice;
  bool wall_occlusion = true;  // tank::SceneLevels::wall_occlusion
};

// The hall's camera (tank::hall_camera) for an image of width x height.
LevelView farm_camera(const tank::Hall& hall, int width, int height);

// Runs the farm and returns its record (docs/benchmarks.md "The farm"). kInvalidArgument
// naming the setting for a bad one (fish, tanks, frames), the scene's errors as they
// come.
nlohmann::ordered_json measure_farm(Context& context, const std::string& mesh,
                                    const std::string& rig, const FarmSettings& settings);

}  // namespace finflex::bench

// The levels of detail of a command's mesh (finflex/detail_levels.hpp), as rig-info and
// check take them: --levels N (the full mesh included) and --triangle-ratio R.
#pragma once

#include <string>

#include "finflex/detail_levels.hpp"

namespace finflex::cli {

// Errors name the option and the value as typed: "--levels '9': ..." (1..8),
// "--triangle-ratio '1': ..." (0 < R < 1). `freeze_fins`: LevelOptions::freeze_fins
// (the bounds: frozen_fin_bounds).
LevelOptions parse_level_options(const std::string& levels, const std::string& triangle_ratio,
                                 bool freeze_fins = false);

// `options` with the value bounds of `model`'s frozen-fin level: a swim rig's
// (SwimModel::value_bounds), else the rig's limits.
LevelOptions frozen_fin_bounds(LevelOptions options, const RiggedMesh& model);

// The commands' --freeze-fins / --no-freeze-fins (default on) and their help.
constexpr const char* kFreezeFinsFlag = "--freeze-fins,!--no-freeze-fins";
constexpr const char* kFreezeFinsHelp =
    "With levels: one more level after the coarsest, its fins frozen (only the body's "
    "stages), its error bound added (default on)";

// The commands' --wall-occlusion / --no-wall-occlusion (default on) and their help.
constexpr const char* kWallOcclusionFlag = "--wall-occlusion,!--no-wall-occlusion";
constexpr const char* kWallOcclusionHelp =
    "With levels: fish behind other tanks' walls are culled (default on; off with --refraction)";

// One line per level: vertices, triangles, the geometric error in mesh units and as a
// fraction of `body_length` (the root frame's length), and whether its fins move.
void print_levels(const DetailLevels& levels, double body_length);

}  // namespace finflex::cli

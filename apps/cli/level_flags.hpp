// The levels of detail of a command's mesh (finflex/detail_levels.hpp), as rig-info and
// check take them: --levels N (the full mesh included) and --triangle-ratio R.
#pragma once

#include <string>

#include "finflex/detail_levels.hpp"

namespace finflex::cli {

// Errors name the option and the value as typed: "--levels '9': ..." (1..8),
// "--triangle-ratio '1': ..." (0 < R < 1).
LevelOptions parse_level_options(const std::string& levels, const std::string& triangle_ratio);

// One line per level: vertices, triangles, the geometric error in mesh units and as a
// fraction of `body_length` (the root frame's length).
void print_levels(const DetailLevels& levels, double body_length);

}  // namespace finflex::cli

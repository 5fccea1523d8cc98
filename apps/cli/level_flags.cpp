#include "level_flags.hpp"

#include <cstdio>

#include "cli_numbers.hpp"
#include "finflex/error.hpp"
#include "finflex/swim.hpp"

namespace finflex::cli {

LevelOptions parse_level_options(const std::string& levels, const std::string& triangle_ratio,
                                 bool freeze_fins) {
  LevelOptions options;
  options.freeze_fins = freeze_fins;
  options.levels = parse_count(levels, "--levels", 1, kMaxDetailLevels,
                               "levels of detail, the full mesh included");
  options.triangle_ratio = parse_number(triangle_ratio, "--triangle-ratio");
  if (!(options.triangle_ratio > 0.0 && options.triangle_ratio < 1.0)) {
    throw Error(ErrorCode::kInvalidArgument, "--triangle-ratio",
                "--triangle-ratio '" + triangle_ratio +
                    "': expected a number between 0 and 1 (each level's share of the finer "
                    "level's triangles)");
  }
  return options;
}

LevelOptions frozen_fin_bounds(LevelOptions options, const RiggedMesh& model) {
  if (!options.freeze_fins) return options;
  try {
    options.value_bounds = SwimModel(model).value_bounds();
  } catch (const Error&) {
    options.value_bounds.clear();  // not a swim rig: the rig's limits
  }
  return options;
}

void print_levels(const DetailLevels& levels, double body_length) {
  std::printf("levels of detail (vertices of a level: the first of the order of level 0):\n");
  std::printf("  %5s %9s %10s %16s %14s %7s\n", "level", "vertices", "triangles", "error (mesh)",
              "error/length", "fins");
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const DetailLevel& level = levels.level(k);
    std::printf("  %5zu %9zu %10zu %16.3g %14.3g %7s\n", k, level.vertex_count,
                level.triangle_count, level.geometric_error, level.geometric_error / body_length,
                level.fins_frozen ? "frozen" : "moving");
  }
}

}  // namespace finflex::cli

// A hall of a recirculating aquaculture system: several tanks (tank.hpp) side by side
// in rows, each with its own fish and current, simulated independently. One tank is
// the default (the hall is then that tank, at the origin); a farm is a hall of many.
//
// World: metres, y up, the floor at y = 0; tank 0's axis on the y axis, the others in
// rows of `columns` along +x, the rows along -z, their axes `spacing()` apart. Fish are
// numbered tank by tank, and within a tank as its fish() are. The defaults and their
// sources are in docs/swimming.md ("A farm hall").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/wall_occlusion.hpp"
#include "tank.hpp"

namespace finflex::tank {

struct HallSettings {
  TankSettings tank;        // every tank's
  std::size_t tanks = 1;    // 1 to 1024
  std::size_t columns = 4;  // tanks per row (1 to 1024)
  double walkway = 1.5;     // m between neighbouring tanks' walls (>= 0)

  HallSettings() = default;
  // One tank with these settings.
  HallSettings(const TankSettings& one) : tank(one) {}  // NOLINT: a tank is a hall of one

  // A farm hall of `tanks` tanks holding `fish` fish in all, each tank scaled from
  // TankSettings{} (diameter and depth alike) to keep its density of 1,000 fish.
  static HallSettings farm(std::size_t tanks, std::size_t fish);
};

// The hall seen by one camera: on the gangway 1 m in front of the first row, 4 m above
// the floor, looking down the hall along its rows at the third row's middle (the last
// row's when there are fewer), a 50-degree vertical field of view.
struct HallCamera {
  glm::dvec3 eye{0.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double vertical_fov_degrees = 50.0;
  double near_plane = 0.1;  // m
  double far_plane = 1.0;   // m: past the last row
};
HallCamera hall_camera(const HallSettings& settings);

class Hall {
 public:
  // `fish_per_species[s]` fish of species s spread over the tanks as evenly as
  // possible (every tank its share of every species, the tanks' totals within one
  // fish); tank t's seed is seed + t.
  // Errors: Tank's (named "tank.*", "fish"), and "hall.tanks", "hall.columns",
  // "hall.walkway" out of their ranges.
  Hall(const HallSettings& settings, const std::vector<std::size_t>& fish_per_species,
       std::uint64_t seed);

  // Every tank one step (Tank::step); several tanks step on as many threads as the
  // machine has, the same result as one after another.
  void step(double dt);

  const HallSettings& hall_settings() const { return settings_; }
  const TankSettings& settings() const { return settings_.tank; }
  std::size_t tank_count() const { return tanks_.size(); }
  const Tank& tank(std::size_t t) const { return tanks_.at(t); }
  // Tank t's axis on the floor, and the distance between neighbouring axes.
  glm::dvec3 centre(std::size_t t) const;
  double spacing() const;
  // Every tank's wall (radius, floor to rim, wall_faces) as an occluder, as the
  // pictures' cut-away tanks draw it (LevelChooser::set_occluders).
  std::vector<WallOccluder> walls() const;
  // Every fish in hall coordinates, tank by tank.
  const std::vector<Fish>& fish() const;
  double time() const { return tanks_.front().time(); }
  // The swim drivers' inputs of species s (hall coordinates), tank by tank; lengths.
  void inputs(std::size_t species, std::vector<SwimInput>& out) const;
  void inputs(std::size_t species, SwimInput* out) const;
  std::vector<float> lengths(std::size_t species) const;
  // Summed over the tanks (Tank::corrections, Tank::brakes).
  std::size_t corrections() const;
  std::size_t brakes() const;

 private:
  HallSettings settings_;
  std::vector<Tank> tanks_;
  std::vector<std::vector<std::size_t>> counts_;  // per tank, its fish of each species
  mutable std::vector<Fish> fish_;                // fish() of the last step, made when asked
  mutable bool fish_current_ = false;
};

}  // namespace finflex::tank

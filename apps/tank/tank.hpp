// A virtual tank of a recirculating aquaculture system (RAS): a round tank with its
// rotating water current and fish that cruise against it, keep off the wall, the floor
// and the surface, keep their distance from their neighbours while schooling with them
// and change speed now and then. It is an example built on FinFlex's public API
// (finflex/swim.hpp): it only computes where each fish is, where it heads and how fast
// it swims; the swim drivers turn that into body waves, fin beats and world placements.
//
// World: metres, y up, the tank's axis on the y axis, the floor at y = 0, the surface
// at y = depth. The current turns counter-clockwise seen from above. The defaults and
// their sources are in docs/swimming.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/swim.hpp"
#include "neighbour_grid.hpp"

namespace finflex::tank {

struct TankSettings {
  // A 3.66 m x 1.22 m "Cornell-type" dual-drain tank (Summerfelt, Davidson & Timmons
  // 2000; diameter:depth 3:1): 1,000 fish of 0.4 m are about 60 kg/m^3, inside the
  // 35-75 kg/m^3 of commercial salmon RAS.
  double diameter = 3.66;
  double depth = 1.22;
  // The wall above the water, a fraction of the depth: the rim at depth (1 + freeboard).
  double freeboard = 0.10;
  double wall_height() const { return depth * (1.0 + freeboard); }
  // The wall's flat faces around, as pictures draw it (8 to 4096).
  int wall_faces = 96;
  // Rotational current u(r) = wall_current r / R, uniform with depth (Davidson &
  // Summerfelt 2004): 1 body length per second at the wall for 0.4 m fish.
  double wall_current = 0.4;
  // Lengths: normal, mean 0.40 m, coefficient of variation 8 %, cut at 3 SD.
  double mean_length = 0.40;
  double length_cv = 0.08;
  // Cruise speed through the water, body lengths per second (Johansson et al. 2014:
  // about 1), varying slowly per fish (Ornstein-Uhlenbeck: relative SD, time constant s).
  double cruise_speed = 1.0;
  double speed_variation = 0.2;
  double speed_time = 20.0;
  // Rare bursts: per fish and second, their speed (body lengths per second) and length (s).
  double burst_rate = 1.0 / 300.0;
  double burst_speed = 4.0;
  double burst_duration = 0.6;
  // Steering: the largest yaw rate (rad/s; routine turns 30-60 degrees per second),
  // the largest pitch (rad), and how far from the wall (body lengths) fish start to turn
  // away; fish keep `clearance` body lengths from the wall, floor and surface.
  double max_yaw_rate = 0.9;
  double max_pitch = 0.35;
  double wall_distance = 1.0;
  double clearance = 0.5;
  // Neighbours closer than this many body lengths push each other apart (or less, at a
  // density where fish cannot keep it: 0.554 (volume per fish)^(1/3)).
  double neighbour_distance = 0.9;
  // Schooling over the same neighbours (Reynolds 1987, "Flocks, herds and schools",
  // SIGGRAPH: separation, alignment, cohesion): a fish also turns towards their mean
  // heading (weight `alignment`) and towards their centre (weight `cohesion`), against
  // the current's pull of weight 1; 0 turns either off.
  double alignment = 0.5;
  double cohesion = 0.1;
};

// One fish's motion: what the swim drivers need (SwimInput) and its length and species.
struct Fish {
  glm::dvec3 position{0.0};
  double yaw = 0.0;    // heading about +y: 0 towards +x, pi/2 towards -z
  double pitch = 0.0;  // nose up
  double speed = 0.0;  // through the water, m/s
  double turn_rate = 0.0;
  double length = 0.4;
  std::size_t species = 0;
  // Behaviour state.
  double speed_factor = 0.0;     // the slow speed variation (relative)
  double burst_left = 0.0;       // seconds of burst left
  double preferred_depth = 0.5;  // the depth it drifts towards (m above the floor)
};

class Tank {
 public:
  // `fish_per_species[s]` fish of species s, placed at random (a given seed gives the
  // same tank). kInvalidArgument naming "fish" (none), "tank.diameter",
  // "tank.depth" (not finite and > 0, or too small for the fish: the diameter must be at
  // least 4 and the depth 2 mean lengths) or another setting out of its domain.
  Tank(const TankSettings& settings, const std::vector<std::size_t>& fish_per_species,
       std::uint64_t seed);

  // Advances every fish by dt seconds (> 0).
  void step(double dt);

  const TankSettings& settings() const { return settings_; }
  const std::vector<Fish>& fish() const { return fish_; }
  double time() const { return time_; }
  // The water's velocity at a point.
  glm::dvec3 current(const glm::dvec3& position) const;
  // The swim drivers' inputs of species s's fish (in order of fish()), and their lengths.
  void inputs(std::size_t species, std::vector<SwimInput>& out) const;
  // The same written into `out`, one entry per fish of the species (a swim driver's
  // ClSwimDriver::staged_inputs()).
  void inputs(std::size_t species, SwimInput* out) const;
  std::vector<float> lengths(std::size_t species) const;
  // Times a fish had to be put back inside the water: its steering and braking failed
  // (0 in the default tank: tests/test_tank.cpp).
  std::size_t corrections() const { return corrections_; }
  // Fish-steps in which a fish braked in front of the wall, floor or surface (covered
  // only part of its swim: it was still turning away).
  std::size_t brakes() const { return brakes_; }

 private:
  TankSettings settings_;
  std::vector<Fish> fish_;
  std::mt19937_64 random_;
  NeighbourGrid grid_;
  double neighbour_distance_ = 0.0;  // m
  // The step's fish positions and headings (heading(yaw)), made once per step for the
  // neighbour queries (contiguous: no Fish read per neighbour, no sine per neighbour).
  std::vector<glm::dvec3> positions_;
  std::vector<glm::dvec3> headings_;
  double time_ = 0.0;
  std::size_t corrections_ = 0;
  std::size_t brakes_ = 0;

  void steer(Fish& fish, double dt);
  // The current's turn of one step dt, as a rotation about +y (its cosine and sine).
  glm::dvec2 current_turn(double dt) const;
  static glm::dvec3 carried(const glm::dvec3& p, const glm::dvec2& turn);
  glm::dvec3 swum(const Fish& fish, const glm::dvec3& p, const glm::dvec3& step);
  void keep_inside(Fish& fish);
};

}  // namespace finflex::tank

// The tank's behaviour model (tank.hpp): each step, every fish steers its heading
// (upstream, away from the wall and from neighbours, along their headings and towards
// their centre, with a slow wander), its pitch
// (towards its preferred depth, away from the floor and the surface) and its speed
// (cruise with a slow variation, rare bursts); then moves with the water (the current's
// rotation turned exactly) and swims, braking where its step would leave the water.
#include "tank.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "finflex/error.hpp"

namespace finflex::tank {
namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + " " + message);
}

double wrapped_angle(double a) { return a - 2.0 * kPi * std::floor((a + kPi) / (2.0 * kPi)); }

// The heading's unit vector for a yaw about +y (0: +x, pi/2: -z).
glm::dvec3 heading(double yaw) { return {std::cos(yaw), 0.0, -std::sin(yaw)}; }

void check(const TankSettings& s) {
  const std::pair<const char*, double> positive[] = {
      {"tank.diameter", s.diameter},       {"tank.depth", s.depth},
      {"tank.mean_length", s.mean_length}, {"tank.cruise_speed", s.cruise_speed},
      {"tank.speed_time", s.speed_time},   {"tank.max_yaw_rate", s.max_yaw_rate},
      {"tank.max_pitch", s.max_pitch},     {"tank.wall_distance", s.wall_distance},
      {"tank.clearance", s.clearance},     {"tank.neighbour_distance", s.neighbour_distance},
      {"tank.burst_speed", s.burst_speed}, {"tank.burst_duration", s.burst_duration}};
  for (const auto& [name, value] : positive) {
    if (!std::isfinite(value) || !(value > 0.0)) {
      fail(name, "= " + std::to_string(value) + " must be finite and > 0");
    }
  }
  if (s.wall_faces < 8 || s.wall_faces > 4096) {
    fail("tank.wall_faces", "= " + std::to_string(s.wall_faces) + " must be 8 to 4096");
  }
  const std::pair<const char*, double> non_negative[] = {
      {"tank.wall_current", s.wall_current}, {"tank.freeboard", s.freeboard},
      {"tank.length_cv", s.length_cv},       {"tank.speed_variation", s.speed_variation},
      {"tank.burst_rate", s.burst_rate},     {"tank.alignment", s.alignment},
      {"tank.cohesion", s.cohesion}};
  for (const auto& [name, value] : non_negative) {
    if (!std::isfinite(value) || value < 0.0) {
      fail(name, "= " + std::to_string(value) + " must be finite and >= 0");
    }
  }
  if (s.length_cv >= 0.3) fail("tank.length_cv", "must be below 0.3");
  if (s.diameter < 4.0 * s.mean_length) {
    fail("tank.diameter", "= " + std::to_string(s.diameter) + " m is too small for fish of " +
                              std::to_string(s.mean_length) + " m (at least 4 lengths)");
  }
  if (s.depth < 2.0 * s.mean_length) {
    fail("tank.depth", "= " + std::to_string(s.depth) + " m is too shallow for fish of " +
                           std::to_string(s.mean_length) + " m (at least 2 lengths)");
  }
}

}  // namespace

Tank::Tank(const TankSettings& settings, const std::vector<std::size_t>& fish_per_species,
           std::uint64_t seed)
    : settings_(settings), random_(seed) {
  check(settings_);
  std::size_t total = 0;
  for (std::size_t count : fish_per_species) total += count;
  if (total == 0) fail("fish", "= 0: at least one fish is needed");
  const double radius = 0.5 * settings_.diameter;
  const double volume = kPi * radius * radius * settings_.depth;
  // Spacing: the free-school distance, or what the density leaves (the mean nearest-
  // neighbour distance of a random arrangement, 0.554 n^(-1/3)).
  neighbour_distance_ = std::min(settings_.neighbour_distance * settings_.mean_length,
                                 0.554 * std::cbrt(volume / double(total)));
  grid_.reset(glm::dvec3(-radius, 0.0, -radius), glm::dvec3(radius, settings_.depth, radius),
              std::max(neighbour_distance_, 0.05));
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t s = 0; s < fish_per_species.size(); ++s) {
    for (std::size_t n = 0; n < fish_per_species[s]; ++n) {
      Fish fish;
      fish.species = s;
      fish.length = settings_.mean_length *
                    (1.0 + settings_.length_cv * std::clamp(normal(random_), -3.0, 3.0));
      const double margin = settings_.clearance * fish.length;
      // Uniform over the water inside the clearances.
      const double r = (radius - margin) * std::sqrt(unit(random_));
      const double angle = 2.0 * kPi * unit(random_);
      fish.position = {r * std::cos(angle),
                       margin + (settings_.depth - 2.0 * margin) * unit(random_),
                       -r * std::sin(angle)};
      fish.preferred_depth = fish.position.y;
      // Upstream: against the current (which turns towards increasing yaw of the position).
      fish.yaw = wrapped_angle(angle - 0.5 * kPi + 0.3 * normal(random_));
      fish.speed_factor = settings_.speed_variation * normal(random_);
      fish.speed = settings_.cruise_speed * fish.length;
      fish_.push_back(fish);
    }
  }
}

glm::dvec3 Tank::current(const glm::dvec3& p) const {
  const double radius = 0.5 * settings_.diameter;
  // Solid-body rotation about +y: u(r) = wall_current r / R along (z, 0, -x) / r.
  return settings_.wall_current / radius * glm::dvec3(p.z, 0.0, -p.x);
}

void Tank::steer(Fish& fish, double dt) {
  const TankSettings& s = settings_;
  const double radius = 0.5 * s.diameter;
  const glm::dvec3 p = fish.position;
  const glm::dvec3 horizontal(p.x, 0.0, p.z);
  const double r = glm::length(horizontal);
  const glm::dvec3 outward = r > 1e-9 ? horizontal / r : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 along_current(outward.z, 0.0, -outward.x);

  // Where to head: upstream, away from the wall, away from neighbours. The wall is
  // felt from wall_distance body lengths, or from two turning radii (speed over the
  // largest yaw rate) when the fish is faster: a bursting fish turns in time too.
  glm::dvec3 want = -along_current;
  const double wall_margin =
      std::max(s.wall_distance * fish.length, 2.0 * fish.speed / s.max_yaw_rate);
  want -= outward * 3.0 * std::clamp((wall_margin - (radius - r)) / wall_margin, 0.0, 1.0);
  double vertical_push = 0.0;
  glm::dvec3 headings(0.0), towards(0.0);  // the neighbours' headings; their offsets
  // Neighbours surely farther than the distance are passed over on their squared
  // distance (with a margin over its rounding: the others are judged as before).
  const double beyond_squared = neighbour_distance_ * neighbour_distance_ * (1.0 + 1e-9);
  grid_.around(p, [&](std::size_t j, const glm::dvec3& position) {
    const glm::dvec3 away = p - position;
    if (glm::dot(away, away) > beyond_squared) return;
    const double distance = glm::length(away);
    if (distance <= 1e-9 || distance >= neighbour_distance_) return;
    const double weight = 2.0 * (neighbour_distance_ - distance) / neighbour_distance_;
    want += glm::dvec3(away.x, 0.0, away.z) / distance * weight;
    vertical_push += away.y / distance * weight;
    headings += headings_[j];
    towards -= glm::dvec3(away.x, 0.0, away.z);
  });
  // Schooling: towards the neighbours' mean heading and their centre.
  if (glm::length(headings) > 1e-9) want += s.alignment * glm::normalize(headings);
  if (glm::length(towards) > 1e-9) want += s.cohesion * glm::normalize(towards);
  const double wanted_yaw = std::atan2(-want.z, want.x);
  const double turn = wrapped_angle(wanted_yaw - fish.yaw);
  const double turn_rate = std::clamp(2.0 * turn, -s.max_yaw_rate, s.max_yaw_rate);
  fish.turn_rate += (turn_rate - fish.turn_rate) * std::min(1.0, dt / 0.3);  // smooth

  // Depth: towards the preferred one (which drifts), off the floor and the surface.
  std::normal_distribution<double> normal(0.0, 1.0);
  const double clearance = s.clearance * fish.length;
  fish.preferred_depth = std::clamp(fish.preferred_depth + 0.05 * std::sqrt(dt) * normal(random_),
                                    clearance, s.depth - clearance);
  // Off the floor and the surface within a body length of them.
  const double floor_gap = (p.y - clearance) / fish.length;
  const double surface_gap = (s.depth - clearance - p.y) / fish.length;
  const double climb =
      (fish.preferred_depth - p.y) / fish.length + 0.5 * std::clamp(vertical_push, -1.0, 1.0) +
      2.0 * std::max(0.0, 1.0 - floor_gap) - 2.0 * std::max(0.0, 1.0 - surface_gap);
  const double pitch = std::clamp(0.8 * climb, -s.max_pitch, s.max_pitch);
  fish.pitch += (pitch - fish.pitch) * std::min(1.0, dt / 0.5);

  // Speed: cruise with a slow variation (Ornstein-Uhlenbeck), and rare bursts.
  fish.speed_factor += -fish.speed_factor * dt / s.speed_time +
                       s.speed_variation * std::sqrt(2.0 * dt / s.speed_time) * normal(random_);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (fish.burst_left <= 0.0 && unit(random_) < s.burst_rate * dt)
    fish.burst_left = s.burst_duration;
  const double body_lengths = fish.burst_left > 0.0
                                  ? s.burst_speed
                                  : std::max(0.1, s.cruise_speed * (1.0 + fish.speed_factor));
  fish.burst_left = std::max(0.0, fish.burst_left - dt);
  fish.speed = body_lengths * fish.length;
}

// The current's part of a step: the solid-body rotation turned exactly (an Euler
// step would carry every fish outwards by r (w dt)^2 / 2 a step).
glm::dvec2 Tank::current_turn(double dt) const {
  const double angle = settings_.wall_current / (0.5 * settings_.diameter) * dt;
  return {std::cos(angle), std::sin(angle)};
}

glm::dvec3 Tank::carried(const glm::dvec3& p, const glm::dvec2& turn) {
  const double c = turn.x, s = turn.y;
  return {p.x * c + p.z * s, p.y, -p.x * s + p.z * c};
}

// The fish's own part of a step, from `p`: where it would leave the water inside the
// clearances it brakes, covering only the part of the step that stays inside (fish
// slow down in front of a wall they are still turning away from).
glm::dvec3 Tank::swum(const Fish& fish, const glm::dvec3& p, const glm::dvec3& step) {
  const double clearance = settings_.clearance * fish.length;
  // A hair inside the bounds, so that rounding never takes the fish across them.
  const double radius = (0.5 * settings_.diameter - clearance) * (1.0 - 1e-9);
  const double low = clearance * (1.0 + 1e-9);
  const double high = (settings_.depth - clearance) * (1.0 - 1e-9);
  double t = 1.0;
  // Horizontally: the largest t with |p + t step| <= radius (p is inside).
  const double a = step.x * step.x + step.z * step.z;
  const double b = p.x * step.x + p.z * step.z;
  const double c = p.x * p.x + p.z * p.z - radius * radius;
  if (a > 0.0 &&
      (p.x + step.x) * (p.x + step.x) + (p.z + step.z) * (p.z + step.z) > radius * radius) {
    t = std::clamp((-b + std::sqrt(std::max(0.0, b * b - a * c))) / a, 0.0, 1.0);
  }
  // Vertically.
  if (p.y + t * step.y > high) t = std::clamp((high - p.y) / step.y, 0.0, t);
  if (p.y + t * step.y < low) t = std::clamp((low - p.y) / step.y, 0.0, t);
  if (t < 1.0) ++brakes_;
  return p + t * step;
}

void Tank::keep_inside(Fish& fish) {
  const double radius = 0.5 * settings_.diameter;
  const double clearance = settings_.clearance * fish.length;
  glm::dvec3& p = fish.position;
  bool corrected = false;
  const double r = std::hypot(p.x, p.z);
  if (r > radius - clearance) {
    const double scale = (radius - clearance) / r;
    p.x *= scale;
    p.z *= scale;
    corrected = true;
  }
  if (p.y < clearance || p.y > settings_.depth - clearance) {
    p.y = std::clamp(p.y, clearance, settings_.depth - clearance);
    corrected = true;
  }
  corrections_ += corrected;
}

void Tank::step(double dt) {
  if (!std::isfinite(dt) || !(dt > 0.0)) fail("dt", "= " + std::to_string(dt) + " must be > 0");
  positions_.clear();
  headings_.clear();
  for (const Fish& fish : fish_) {
    positions_.push_back(fish.position);
    headings_.push_back(heading(fish.yaw));  // steer() leaves every yaw as it is
  }
  grid_.build(positions_);
  for (Fish& fish : fish_) steer(fish, dt);
  const glm::dvec2 turn = current_turn(dt);
  for (Fish& fish : fish_) {
    fish.yaw = wrapped_angle(fish.yaw + fish.turn_rate * dt);
    const glm::dvec3 swim = fish.speed * std::cos(fish.pitch) * heading(fish.yaw) +
                            glm::dvec3(0.0, fish.speed * std::sin(fish.pitch), 0.0);
    fish.position = swum(fish, carried(fish.position, turn), swim * dt);
    keep_inside(fish);
  }
  time_ += dt;
}

void Tank::inputs(std::size_t species, std::vector<SwimInput>& out) const {
  out.resize(static_cast<std::size_t>(std::count_if(
      fish_.begin(), fish_.end(), [&](const Fish& fish) { return fish.species == species; })));
  inputs(species, out.data());
}

void Tank::inputs(std::size_t species, SwimInput* out) const {
  for (const Fish& fish : fish_) {
    if (fish.species != species) continue;
    SwimInput& in = *out++;
    in.position = glm::vec3(fish.position);
    in.yaw = static_cast<float>(fish.yaw);
    in.pitch = static_cast<float>(fish.pitch);
    in.speed = static_cast<float>(fish.speed);
    in.turn_rate = static_cast<float>(fish.turn_rate);
  }
}

std::vector<float> Tank::lengths(std::size_t species) const {
  std::vector<float> lengths;
  for (const Fish& fish : fish_) {
    if (fish.species == species) lengths.push_back(static_cast<float>(fish.length));
  }
  return lengths;
}

}  // namespace finflex::tank

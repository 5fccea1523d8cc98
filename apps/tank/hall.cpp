#include "hall.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::tank {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + " " + message);
}

}  // namespace

HallSettings HallSettings::farm(std::size_t tanks, std::size_t fish) {
  HallSettings out;
  out.tanks = std::max<std::size_t>(1, tanks);
  const double per_tank = double(fish) / double(out.tanks);
  const double scale = std::max(1.0, std::cbrt(per_tank / 1000.0));
  out.tank.diameter *= scale;
  out.tank.depth *= scale;
  return out;
}

HallCamera hall_camera(const HallSettings& settings) {
  const std::size_t tanks = std::max<std::size_t>(settings.tanks, 1);
  const std::size_t columns = std::max<std::size_t>(settings.columns, 1);
  const double spacing = settings.tank.diameter + settings.walkway;
  const double rows = double((tanks + columns - 1) / columns);
  const double middle_x = 0.5 * (double(std::min(tanks, columns)) - 1.0) * spacing;
  const double front = 0.5 * settings.tank.diameter + 1.0;
  HallCamera camera;
  camera.eye = {middle_x, 4.0, front};
  camera.target = {middle_x, 0.0, -std::min(2.0, rows - 1.0) * spacing};
  camera.far_plane = (rows + 1.0) * spacing + front;
  return camera;
}

Hall::Hall(const HallSettings& settings, const std::vector<std::size_t>& fish_per_species,
           std::uint64_t seed)
    : settings_(settings) {
  if (settings_.tanks < 1 || settings_.tanks > 1024) {
    fail("hall.tanks", "= " + std::to_string(settings_.tanks) + " must be 1 to 1024");
  }
  if (settings_.columns < 1 || settings_.columns > 1024) {
    fail("hall.columns", "= " + std::to_string(settings_.columns) + " must be 1 to 1024");
  }
  if (!std::isfinite(settings_.walkway) || settings_.walkway < 0.0) {
    fail("hall.walkway", "= " + std::to_string(settings_.walkway) + " must be finite and >= 0");
  }
  std::size_t total = 0;
  for (std::size_t count : fish_per_species) total += count;
  if (total < settings_.tanks) {
    fail("fish", "= " + std::to_string(total) + ": every one of the " +
                     std::to_string(settings_.tanks) + " tanks needs a fish");
  }
  tanks_.reserve(settings_.tanks);
  const std::size_t tanks = settings_.tanks;
  for (std::size_t t = 0; t < tanks; ++t) {
    // Each species' remainder goes to the tanks after the previous species' remainder,
    // so that the tanks' totals differ by one fish at most.
    std::vector<std::size_t> share;
    std::size_t start = 0;
    for (std::size_t count : fish_per_species) {
      const std::size_t extra = count % tanks;
      share.push_back(count / tanks + ((t + tanks - start) % tanks < extra ? 1 : 0));
      start = (start + extra) % tanks;
    }
    // A tank whose share of every species rounds to 0 takes one of the largest.
    std::size_t sum = 0;
    for (std::size_t n : share) sum += n;
    if (sum == 0) {
      share[std::size_t(std::max_element(fish_per_species.begin(), fish_per_species.end()) -
                        fish_per_species.begin())] = 1;
    }
    tanks_.emplace_back(settings_.tank, share, seed + t);
    counts_.push_back(share);
  }
}

double Hall::spacing() const { return settings_.tank.diameter + settings_.walkway; }

glm::dvec3 Hall::centre(std::size_t t) const {
  const std::size_t column = t % settings_.columns, row = t / settings_.columns;
  return {double(column) * spacing(), 0.0, -double(row) * spacing()};
}

std::vector<WallOccluder> Hall::walls() const {
  const TankSettings& tank = settings_.tank;
  std::vector<WallOccluder> out;
  for (std::size_t t = 0; t < tanks_.size(); ++t) {
    out.push_back({centre(t), 0.5 * tank.diameter, tank.wall_height(), tank.wall_faces});
  }
  return out;
}

void Hall::step(double dt) {
  // The tanks share nothing: with several, they step on threads of their own, each
  // thread a fixed share of the tanks (the same result on any count of threads).
  const std::size_t threads =
      std::min<std::size_t>(tanks_.size(), std::max(1u, std::thread::hardware_concurrency()));
  if (threads <= 1) {
    for (Tank& tank : tanks_) tank.step(dt);
  } else {
    std::vector<std::thread> workers;
    for (std::size_t w = 0; w < threads; ++w) {
      workers.emplace_back([this, w, threads, dt] {
        for (std::size_t t = w; t < tanks_.size(); t += threads) tanks_[t].step(dt);
      });
    }
    for (std::thread& worker : workers) worker.join();
  }
  fish_current_ = false;
}

const std::vector<Fish>& Hall::fish() const {
  if (tanks_.size() == 1) return tanks_.front().fish();
  if (!fish_current_) {
    fish_.clear();
    for (std::size_t t = 0; t < tanks_.size(); ++t) {
      for (Fish fish : tanks_[t].fish()) {
        fish.position += centre(t);
        fish_.push_back(fish);
      }
    }
    fish_current_ = true;
  }
  return fish_;
}

void Hall::inputs(std::size_t species, std::vector<SwimInput>& out) const {
  std::size_t count = 0;
  for (const std::vector<std::size_t>& counts : counts_)
    count += species < counts.size() ? counts[species] : 0;
  out.resize(count);
  inputs(species, out.data());
}

// Each tank's inputs, their positions moved to the hall in double precision (the
// float of the hall position, as a single tank's are the float of its position).
void Hall::inputs(std::size_t species, SwimInput* out) const {
  for (std::size_t t = 0; t < tanks_.size(); ++t) {
    tanks_[t].inputs(species, out);
    if (t == 0) {  // at the origin: the tank's own positions
      out += species < counts_[t].size() ? counts_[t][species] : 0;
      continue;
    }
    for (const Fish& fish : tanks_[t].fish()) {
      if (fish.species == species) (out++)->position = glm::vec3(fish.position + centre(t));
    }
  }
}

std::vector<float> Hall::lengths(std::size_t species) const {
  std::vector<float> out;
  for (const Tank& tank : tanks_) {
    const std::vector<float> one = tank.lengths(species);
    out.insert(out.end(), one.begin(), one.end());
  }
  return out;
}

std::size_t Hall::corrections() const {
  std::size_t sum = 0;
  for (const Tank& tank : tanks_) sum += tank.corrections();
  return sum;
}

std::size_t Hall::brakes() const {
  std::size_t sum = 0;
  for (const Tank& tank : tanks_) sum += tank.brakes();
  return sum;
}

}  // namespace finflex::tank

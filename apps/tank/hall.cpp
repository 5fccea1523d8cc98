#include "hall.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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

void Hall::step(double dt) {
  for (Tank& tank : tanks_) tank.step(dt);
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

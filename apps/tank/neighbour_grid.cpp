#include "neighbour_grid.hpp"

#include <algorithm>
#include <cmath>

namespace finflex::tank {

void NeighbourGrid::reset(const glm::dvec3& low, const glm::dvec3& high, double cell) {
  low_ = low;
  cell_ = cell;
  const glm::dvec3 extent = (high - low) / cell;
  size_ = glm::ivec3(std::max(1, int(std::ceil(extent.x))), std::max(1, int(std::ceil(extent.y))),
                     std::max(1, int(std::ceil(extent.z))));
  start_.assign(std::size_t(size_.x) * std::size_t(size_.y) * std::size_t(size_.z) + 1, 0);
}

glm::ivec3 NeighbourGrid::cell_of(const glm::dvec3& p) const {
  const glm::dvec3 c = glm::floor((p - low_) / cell_);
  return glm::clamp(glm::ivec3(c), glm::ivec3(0), size_ - glm::ivec3(1));
}

void NeighbourGrid::build(const std::vector<glm::dvec3>& points) {
  std::fill(start_.begin(), start_.end(), 0);
  cells_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells_[i] = flat(cell_of(points[i]));
    ++start_[cells_[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  order_.resize(points.size());
  sorted_.resize(points.size());
  next_.assign(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t at = next_[cells_[i]]++;
    order_[at] = i;
    sorted_[at] = points[i];
  }
}

}  // namespace finflex::tank

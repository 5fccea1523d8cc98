// A uniform grid over the tank for neighbour queries: every step the fish are sorted
// into cells (a counting sort, O(n)); a query visits the 27 cells around a point, so
// work stays proportional to the fish, never to their pairs.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace finflex::tank {

class NeighbourGrid {
 public:
  // Cells of `cell` metres over the box [low, high].
  void reset(const glm::dvec3& low, const glm::dvec3& high, double cell);
  void build(const std::vector<glm::dvec3>& points);
  // Calls visit(j, point j) for every point j in the cells around `p` (within one
  // cell), cell by cell in x, then y, then z, and within a cell in the points' order.
  // The three cells of a row are neighbours in the sorted points: one run each.
  template <typename Visit>
  void around(const glm::dvec3& p, Visit visit) const {
    const glm::ivec3 c = cell_of(p);
    const glm::ivec3 low = glm::max(c - 1, glm::ivec3(0));
    const glm::ivec3 high = glm::min(c + 1, size_ - 1);
    for (int z = low.z; z <= high.z; ++z) {
      for (int y = low.y; y <= high.y; ++y) {
        const std::size_t end = start_[flat(glm::ivec3(high.x, y, z)) + 1];
        for (std::size_t k = start_[flat(glm::ivec3(low.x, y, z))]; k < end; ++k) {
          visit(order_[k], sorted_[k]);
        }
      }
    }
  }

 private:
  glm::dvec3 low_{0.0};
  double cell_ = 1.0;
  glm::ivec3 size_{1};
  std::vector<std::size_t> start_;  // per cell, its first entry in order_ (+ the end)
  std::vector<std::size_t> order_;  // point indices sorted by cell
  std::vector<glm::dvec3> sorted_;  // the points in that order
  // build()'s scratch, kept between steps: each point's cell, each cell's next entry.
  std::vector<std::size_t> cells_, next_;

  glm::ivec3 cell_of(const glm::dvec3& p) const;
  std::size_t flat(const glm::ivec3& c) const {
    return (std::size_t(c.z) * std::size_t(size_.y) + std::size_t(c.y)) * std::size_t(size_.x) +
           std::size_t(c.x);
  }
};

}  // namespace finflex::tank

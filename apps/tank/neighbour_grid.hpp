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
  // Calls visit(j) for every point j in the cells around `p` (within one cell).
  template <typename Visit>
  void around(const glm::dvec3& p, Visit visit) const {
    const glm::ivec3 c = cell_of(p);
    for (int z = c.z - 1; z <= c.z + 1; ++z) {
      for (int y = c.y - 1; y <= c.y + 1; ++y) {
        for (int x = c.x - 1; x <= c.x + 1; ++x) {
          if (x < 0 || y < 0 || z < 0 || x >= size_.x || y >= size_.y || z >= size_.z) continue;
          const std::size_t index = flat(glm::ivec3(x, y, z));
          for (std::size_t k = start_[index]; k < start_[index + 1]; ++k) visit(order_[k]);
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

  glm::ivec3 cell_of(const glm::dvec3& p) const;
  std::size_t flat(const glm::ivec3& c) const {
    return (std::size_t(c.z) * std::size_t(size_.y) + std::size_t(c.y)) * std::size_t(size_.x) +
           std::size_t(c.x);
  }
};

}  // namespace finflex::tank

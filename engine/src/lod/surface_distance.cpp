#include "surface_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace finflex::detail {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The distance from p to the triangle abc: the closest point found from the Voronoi
// region of the triangle p lies in (a vertex, an edge or the face).
double distance_to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return glm::length(ap);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return glm::length(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return glm::length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return std::min({glm::length(ap), glm::length(bp), glm::length(cp)});
  return glm::length(p - (a + ab * (vb / sum) + ac * (vc / sum)));
}

// The triangles of a surface in a uniform grid of about one cell per triangle (each
// triangle in every cell its box overlaps), for nearest-triangle queries.
class TriangleGrid {
 public:
  explicit TriangleGrid(const SurfaceView& surface) : surface_(surface) {
    const std::vector<glm::vec3>& positions = *surface.positions;
    const std::vector<std::uint32_t>& indices = *surface.indices;
    const std::size_t triangles = indices.size() / 3;
    lo_ = glm::dvec3(kInfinity);
    glm::dvec3 hi(-kInfinity);
    for (std::uint32_t v : indices) {
      lo_ = glm::min(lo_, glm::dvec3(positions[v]));
      hi = glm::max(hi, glm::dvec3(positions[v]));
    }
    const glm::dvec3 extent = glm::max(hi - lo_, glm::dvec3(1e-9));
    cell_ = std::cbrt(extent.x * extent.y * extent.z / double(std::max<std::size_t>(1, triangles)));
    cell_ = std::max(cell_, 1e-3 * std::max({extent.x, extent.y, extent.z}));
    for (int axis = 0; axis < 3; ++axis) {
      dims_[axis] = std::clamp(int(std::ceil(extent[axis] / cell_)), 1, 256);
    }
    cells_.resize(std::size_t(dims_[0]) * std::size_t(dims_[1]) * std::size_t(dims_[2]));
    for (std::size_t t = 0; t < triangles; ++t) {
      glm::dvec3 box_lo(kInfinity), box_hi(-kInfinity);
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 p(positions[indices[3 * t + std::size_t(k)]]);
        box_lo = glm::min(box_lo, p);
        box_hi = glm::max(box_hi, p);
      }
      const std::array<int, 3> from = cell_of(box_lo), to = cell_of(box_hi);
      for (int x = from[0]; x <= to[0]; ++x)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int z = from[2]; z <= to[2]; ++z) cells_[index(x, y, z)].push_back(std::uint32_t(t));
    }
    seen_.assign(triangles, 0);
  }

  // The distance from p to the surface: rings of cells around p's cell until no cell
  // further out can hold a nearer triangle; a point outside the grid tries them all.
  double distance(const glm::dvec3& p) {
    ++query_;
    double best = kInfinity;
    const glm::dvec3 at = (p - lo_) / cell_;
    const bool inside = at.x >= 0.0 && at.y >= 0.0 && at.z >= 0.0 && at.x < dims_[0] &&
                        at.y < dims_[1] && at.z < dims_[2];
    if (!inside) {
      for (std::size_t t = 0; t < seen_.size(); ++t) best = std::min(best, to_triangle(p, t));
      return best;
    }
    const std::array<int, 3> centre = cell_of(p);
    const int rings = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r <= rings; ++r) {
      for (int x = centre[0] - r; x <= centre[0] + r; ++x) {
        for (int y = centre[1] - r; y <= centre[1] + r; ++y) {
          for (int z = centre[2] - r; z <= centre[2] + r; ++z) {
            const int ring = std::max(
                {std::abs(x - centre[0]), std::abs(y - centre[1]), std::abs(z - centre[2])});
            if (ring != r || x < 0 || y < 0 || z < 0 || x >= dims_[0] || y >= dims_[1] ||
                z >= dims_[2]) {
              continue;
            }
            for (std::uint32_t t : cells_[index(x, y, z)]) {
              if (seen_[t] == query_) continue;
              seen_[t] = query_;
              best = std::min(best, to_triangle(p, t));
            }
          }
        }
      }
      // Every cell of ring r + 1 and beyond is at least r cells from p's own.
      if (best <= double(r) * cell_) break;
    }
    return best;
  }

 private:
  std::array<int, 3> cell_of(const glm::dvec3& p) const {
    std::array<int, 3> c{};
    for (int axis = 0; axis < 3; ++axis) {
      c[axis] = std::clamp(int(std::floor((p[axis] - lo_[axis]) / cell_)), 0, dims_[axis] - 1);
    }
    return c;
  }
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(x) * std::size_t(dims_[1]) + std::size_t(y)) * std::size_t(dims_[2]) +
           std::size_t(z);
  }
  double to_triangle(const glm::dvec3& p, std::size_t t) const {
    const std::vector<glm::vec3>& positions = *surface_.positions;
    const std::uint32_t* v = surface_.indices->data() + 3 * t;
    return distance_to_triangle(p, glm::dvec3(positions[v[0]]), glm::dvec3(positions[v[1]]),
                                glm::dvec3(positions[v[2]]));
  }

  SurfaceView surface_;
  glm::dvec3 lo_{0.0};
  double cell_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> seen_;  // the last query that tested each triangle
  std::uint32_t query_ = 0;
};

// The vertices a surface's triangles use.
std::vector<glm::dvec3> used_vertices(const SurfaceView& surface) {
  std::vector<bool> used(surface.positions->size(), false);
  for (std::uint32_t v : *surface.indices) used[v] = true;
  std::vector<glm::dvec3> out;
  for (std::size_t v = 0; v < used.size(); ++v) {
    if (used[v]) out.emplace_back((*surface.positions)[v]);
  }
  return out;
}

}  // namespace

double farthest_from(const std::vector<glm::dvec3>& points, const SurfaceView& surface) {
  if (points.empty()) return 0.0;
  if (surface.indices->size() < 3) return kInfinity;
  TriangleGrid grid(surface);
  double worst = 0.0;
  for (const glm::dvec3& p : points) worst = std::max(worst, grid.distance(p));
  return worst;
}

double surface_distance(const SurfaceView& coarse, const SurfaceView& fine) {
  std::vector<glm::dvec3> samples = used_vertices(coarse);
  const std::vector<glm::vec3>& positions = *coarse.positions;
  const std::vector<std::uint32_t>& indices = *coarse.indices;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]),
        c(positions[indices[t + 2]]);
    samples.push_back((a + b + c) / 3.0);
    samples.push_back(0.5 * (a + b));
    samples.push_back(0.5 * (b + c));
    samples.push_back(0.5 * (c + a));
  }
  return std::max(farthest_from(used_vertices(fine), coarse), farthest_from(samples, fine));
}

}  // namespace finflex::detail

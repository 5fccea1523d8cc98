// How far apart two triangle surfaces are: the levels of detail's measured error
// (detail_levels.cpp). Point-to-triangle distances (closest point on a triangle, by
// its Voronoi regions) over a uniform grid of the triangles.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace finflex::detail {

// A surface: vertex positions and triangles (3 indices each, into positions).
struct SurfaceView {
  const std::vector<glm::vec3>* positions = nullptr;
  const std::vector<std::uint32_t>* indices = nullptr;
};

// The largest distance from any of `points` to the nearest point of `surface`
// (0 for no points; infinity for a surface without triangles).
double farthest_from(const std::vector<glm::dvec3>& points, const SurfaceView& surface);

// The two-sided distance between `coarse` and `fine` sampled at every vertex of each
// and at the middle and the edge midpoints of each of coarse's triangles (where a
// coarse surface that keeps a subset of the vertices departs from the fine one).
double surface_distance(const SurfaceView& coarse, const SurfaceView& fine);

}  // namespace finflex::detail

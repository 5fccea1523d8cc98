// Private: assembles the Mesh a reader found, with the rules every reader shares
// (finflex/mesh_io.hpp): polygons fan-triangulated around their first corner in file
// order; the normals given for a vertex (OBJ: one per face corner) folded into one;
// the first texcoord given for a vertex kept.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "finflex/mesh.hpp"

namespace finflex::io {

// The positions (0-based, into `corners`) of two corners that name the same vertex,
// the pair with the lowest second position, or nothing if all are distinct.
// O(n log n) for long polygons.
template <typename Index>
std::optional<std::pair<std::size_t, std::size_t>> find_repeated_corner(
    const std::vector<Index>& corners) {
  constexpr std::size_t kShort = 16;  // below this, comparing all pairs is cheapest
  const std::size_t n = corners.size();
  if (n <= kShort) {
    for (std::size_t j = 1; j < n; ++j) {
      for (std::size_t i = 0; i < j; ++i) {
        if (corners[i] == corners[j]) return std::make_pair(i, j);
      }
    }
    return std::nullopt;
  }
  std::vector<std::pair<Index, std::size_t>> sorted(n);
  for (std::size_t k = 0; k < n; ++k) sorted[k] = {corners[k], k};
  std::sort(sorted.begin(), sorted.end());
  std::optional<std::pair<std::size_t, std::size_t>> first;
  for (std::size_t k = 1; k < n; ++k) {
    if (sorted[k].first != sorted[k - 1].first) continue;
    const std::pair<std::size_t, std::size_t> pair(sorted[k - 1].second, sorted[k].second);
    if (!first || pair.second < first->second) first = pair;
  }
  return first;
}

class MeshBuilder {
 public:
  // Appends a vertex and returns its index. Throws kFormat past 2^32 - 1 vertices.
  std::uint32_t add_vertex(const glm::vec3& position);
  std::size_t vertex_count() const { return positions_.size(); }

  // One normal given for `vertex` (an existing one).
  void add_normal(std::uint32_t vertex, const glm::vec3& normal);
  // A texcoord for `vertex` (an existing one), kept only if it is the first.
  void add_texcoord(std::uint32_t vertex, const glm::vec2& texcoord);

  // Appends the triangles (c[0], c[k], c[k + 1]) of a polygon whose corners the
  // reader has checked: at least 3, distinct, existing vertices.
  void add_polygon(const std::vector<std::uint32_t>& corners);

  // The mesh. Normals: none if no vertex was given one; else per vertex the one given
  // (the same for every corner), or the normalized sum of those given, or, for a
  // vertex without one or with a zero sum, the area-weighted normal. Texcoords: none
  // if no vertex was given one; else (0, 0) for the vertices without.
  Mesh finish();

 private:
  // The normals given for one vertex.
  struct NormalSlot {
    std::uint32_t count = 0;
    bool all_equal = true;
    glm::vec3 first{0.0f};
    glm::dvec3 sum{0.0};
  };

  std::vector<glm::vec3> positions_;
  std::vector<std::uint32_t> indices_;
  std::vector<NormalSlot> normals_;   // empty until a vertex gets a normal
  std::vector<glm::vec2> texcoords_;  // empty until a vertex gets a texcoord
  std::vector<bool> has_texcoord_;
};

}  // namespace finflex::io

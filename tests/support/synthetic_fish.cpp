#include "support/synthetic_fish.hpp"

#include <cmath>

namespace finflex::test {

Mesh synthetic_fish(int rings, int segments, bool with_tangents) {
  const double pi = std::acos(-1.0);
  Mesh mesh;
  // Poles at x = -0.5 (tail) and x = +0.5 (head), rings in between.
  mesh.positions.emplace_back(-0.5f, 0.0f, 0.0f);
  for (int r = 1; r < rings - 1; ++r) {
    const double t = static_cast<double>(r) / (rings - 1);  // 0 tail .. 1 head
    const double x = -0.5 + t;
    const double profile = std::sin(pi * t) * (0.6 + 0.4 * t);  // thicker towards the head
    const double height = 0.12 * profile, width = 0.05 * profile;
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * pi * s / segments;
      mesh.positions.emplace_back(static_cast<float>(x), static_cast<float>(height * std::cos(a)),
                                  static_cast<float>(width * std::sin(a)));
    }
  }
  mesh.positions.emplace_back(0.5f, 0.0f, 0.0f);
  const auto ring_vertex = [&](int r, int s) {
    return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  const auto tail = 0u;
  const auto head = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  for (int s = 0; s < segments; ++s) {
    mesh.indices.insert(mesh.indices.end(), {tail, ring_vertex(1, s), ring_vertex(1, s + 1)});
    for (int r = 1; r < rings - 2; ++r) {
      const auto a = ring_vertex(r, s), b = ring_vertex(r, s + 1);
      const auto c = ring_vertex(r + 1, s), d = ring_vertex(r + 1, s + 1);
      mesh.indices.insert(mesh.indices.end(), {a, c, d, a, d, b});
    }
    mesh.indices.insert(mesh.indices.end(),
                        {head, ring_vertex(rings - 2, s + 1), ring_vertex(rings - 2, s)});
  }
  compute_vertex_normals(mesh);
  if (with_tangents) {
    for (const glm::vec3& n : mesh.normals) {
      // Unit tangent orthogonal to the normal, as close to +x as possible.
      glm::vec3 t = glm::vec3(1.0f, 0.0f, 0.0f) - n.x * n;
      if (glm::length(t) < 1e-3f) t = glm::vec3(0.0f, 1.0f, 0.0f) - n.y * n;
      mesh.tangents.emplace_back(glm::normalize(t), 1.0f);
    }
  }
  return mesh;
}

Mesh spine_ribbon(int samples, double half_length, double width) {
  Mesh mesh;
  for (int row = 0; row < 2; ++row) {
    for (int i = 0; i < samples; ++i) {
      const double x = -half_length + 2.0 * half_length * i / (samples - 1);
      mesh.positions.emplace_back(static_cast<float>(x), static_cast<float>(row * width), 0.0f);
      mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  }
  const auto n = static_cast<std::uint32_t>(samples);
  for (std::uint32_t i = 0; i + 1 < n; ++i) {
    mesh.indices.insert(mesh.indices.end(), {i, i + 1, n + i + 1, i, n + i + 1, n + i});
  }
  return mesh;
}

}  // namespace finflex::test

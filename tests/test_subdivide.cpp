// Loop subdivision of the bundled control cage: counts, topology and bad input.
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "finflex/error.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/subdivide.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

std::size_t edge_count(const Mesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = mesh.indices[3 * t + k], b = mesh.indices[3 * t + (k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return edges.size();
}

long euler_characteristic(const Mesh& mesh) {
  return static_cast<long>(mesh.vertex_count()) - static_cast<long>(edge_count(mesh)) +
         static_cast<long>(mesh.triangle_count());
}

TEST(Subdivide, EachLevelSplitsEveryTriangleInFourAndKeepsTheTopology) {
  const Mesh cage = load_mesh(test::data_path("blub/fish_control_mesh.obj"));
  const Mesh once = subdivide_loop(cage, 1);
  EXPECT_EQ(once.triangle_count(), 4 * cage.triangle_count());
  EXPECT_EQ(once.vertex_count(), cage.vertex_count() + edge_count(cage));  // a new vertex per edge
  EXPECT_EQ(euler_characteristic(once), euler_characteristic(cage));
  const Mesh dense = subdivide_loop(cage, 5);
  EXPECT_EQ(dense.triangle_count(), cage.triangle_count() << 10);
  EXPECT_GT(dense.vertex_count(), 100000u);  // the benchmarks' 100k+ vertex fish
  EXPECT_EQ(dense.vertex_count(), 112642u);  // README and docs/benchmarks.md quote it
  EXPECT_NO_THROW(validate_mesh(dense));
  EXPECT_EQ(subdivide_loop(cage, 0).indices, cage.indices);
}

TEST(Subdivide, RejectsBadInput) {
  const Mesh cage = load_mesh(test::data_path("blub/fish_control_mesh.obj"));
  EXPECT_THROW(subdivide_loop(cage, -1), Error);
  EXPECT_THROW(subdivide_loop(cage, 9), Error);
  Mesh points;
  points.positions = {{0, 0, 0}, {1, 0, 0}};
  points.normals = {{0, 0, 1}, {0, 0, 1}};
  EXPECT_THROW(subdivide_loop(points, 1), Error);
}

}  // namespace
}  // namespace finflex

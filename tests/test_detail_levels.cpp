// Levels of detail (finflex/detail_levels.hpp) of the bundled fish: one vertex order
// whose prefixes are the levels, the rig carried over (fins stay fins), each level's
// deformation on the device against the double reference, and a kept vertex deformed
// exactly as the full mesh deforms it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

RiggedMesh load_model(const char* mesh_file, const char* rig_file) {
  Mesh mesh = load_mesh(test::data_path(mesh_file));
  compute_vertex_normals(mesh);
  return RiggedMesh(mesh, resolve_rig(load_rig_file(test::data_path(rig_file)), mesh));
}

const RiggedMesh& blub() {
  static const RiggedMesh model = load_model("blub/fish.obj", "rigs/blub_swim.rig.json");
  return model;
}

const RiggedMesh& barramundi() {
  static const RiggedMesh model =
      load_model("barramundi/BarramundiFish.gltf", "rigs/barramundi_swim.rig.json");
  return model;
}

class BundledLevels : public ::testing::TestWithParam<const char*> {
 protected:
  const RiggedMesh& model() const {
    return std::string(GetParam()) == "blub" ? blub() : barramundi();
  }
};

TEST_P(BundledLevels, CoarserLevelsArePrefixesOfOneVertexOrder) {
  const RiggedMesh& full = model();
  const DetailLevels levels = make_detail_levels(full, LevelOptions{});
  ASSERT_EQ(levels.size(), 4u);
  const DetailLevel& finest = levels.level(0);
  EXPECT_EQ(finest.vertex_count, full.vertex_count());
  EXPECT_EQ(finest.triangle_count, full.mesh().triangle_count());
  EXPECT_EQ(finest.geometric_error, 0.0);
  // full_vertex_of is a permutation, and level 0 is the input in that order.
  const std::vector<std::uint32_t>& from = levels.full_vertex_of();
  ASSERT_EQ(from.size(), full.vertex_count());
  EXPECT_EQ(std::set<std::uint32_t>(from.begin(), from.end()).size(), from.size());
  for (std::size_t v = 0; v < from.size(); ++v) {
    ASSERT_EQ(finest.model.mesh().positions[v], full.mesh().positions[from[v]]) << v;
  }
  std::multiset<std::set<std::uint32_t>> input_triangles, level0_triangles;
  for (std::size_t t = 0; t < full.mesh().triangle_count(); ++t) {
    const std::uint32_t* a = &full.mesh().indices[3 * t];
    const std::uint32_t* b = &finest.model.mesh().indices[3 * t];
    input_triangles.insert({a[0], a[1], a[2]});
    level0_triangles.insert({from[b[0]], from[b[1]], from[b[2]]});
  }
  EXPECT_EQ(input_triangles, level0_triangles);
  for (std::size_t k = 1; k < levels.size(); ++k) {
    const DetailLevel& level = levels.level(k);
    const DetailLevel& finer = levels.level(k - 1);
    EXPECT_LT(level.vertex_count, finer.vertex_count) << "level " << k;
    EXPECT_LE(double(level.triangle_count), 0.75 * double(finer.triangle_count)) << "level " << k;
    EXPECT_GT(level.geometric_error, finer.geometric_error) << "level " << k;
    EXPECT_LT(level.geometric_error, 0.25 * full.rig().components.front().frame.length);
    for (std::size_t v = 0; v < level.vertex_count; ++v) {
      ASSERT_EQ(level.model.mesh().positions[v], finest.model.mesh().positions[v]) << k << " " << v;
      ASSERT_EQ(level.model.mesh().normals[v], finest.model.mesh().normals[v]) << k << " " << v;
    }
    for (std::uint32_t index : level.model.mesh().indices) ASSERT_LT(index, level.vertex_count);
  }
}

TEST_P(BundledLevels, EveryLevelKeepsEveryComponentWhereItWas) {
  const RiggedMesh& full = model();
  const DetailLevels levels = make_detail_levels(full, LevelOptions{});
  const std::vector<std::size_t>& component_of_full = levels.level(0).model.component_of_vertex();
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const RiggedMesh& level = levels.level(k).model;
    ASSERT_EQ(level.rig().components.size(), full.rig().components.size());
    std::vector<std::size_t> triangles_of(level.rig().components.size(), 0);
    const std::vector<std::uint32_t>& indices = level.mesh().indices;
    for (std::size_t t = 0; t < level.mesh().triangle_count(); ++t) {
      const std::size_t c = level.component_of_vertex()[indices[3 * t]];
      if (level.component_of_vertex()[indices[3 * t + 1]] == c &&
          level.component_of_vertex()[indices[3 * t + 2]] == c) {
        ++triangles_of[c];
      }
    }
    for (std::size_t c = 0; c < level.rig().components.size(); ++c) {
      const RigComponent& component = level.rig().components[c];
      EXPECT_GT(triangles_of[c], 0u) << "level " << k << ", " << component.name;
      // The same frames and stages as the full rig's.
      EXPECT_EQ(component.frame.origin, full.rig().components[c].frame.origin);
      EXPECT_EQ(component.chain.size(), full.rig().components[c].chain.size());
    }
    for (std::size_t v = 0; v < level.vertex_count(); ++v) {
      ASSERT_EQ(level.component_of_vertex()[v], component_of_full[v]) << k << " " << v;
    }
  }
}

TEST_P(BundledLevels, EachLevelDeformsOnTheDeviceAsTheReferenceAndAsTheFullMesh) {
  const RiggedMesh& full = model();
  const DetailLevels levels = make_detail_levels(full, LevelOptions{});
  const RigParameters values = test::at_fractions_of_the_limits(full, {0.0, 0.45, -0.8, 1.0});
  const DeformedBatch<double> finest =
      run_reference(levels.level(0).model, values, NormalMode::kRotate);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const RiggedMesh& level = levels.level(k).model;
    const DeformedBatch<double> reference = run_reference(level, values, NormalMode::kRotate);
    for (std::size_t i = 0; i < values.instance_count(); ++i) {
      for (std::size_t v = 0; v < level.vertex_count(); ++v) {
        ASSERT_EQ(reference.position(i, v), finest.position(i, v)) << k << " " << i << " " << v;
        ASSERT_EQ(reference.normal(i, v), finest.normal(i, v)) << k << " " << i << " " << v;
      }
    }
    // On the device: the first coarser level and the coarsest (each level is a program
    // of its own to build).
    if (k != 1 && k + 1 != levels.size()) continue;
    ClDeformer deformer(test::shared_context(), level);
    const DeformedBatch<float> device = test::run_on_device(deformer, values, NormalMode::kRotate);
    const AccuracyReport report =
        compare_to_reference(level, values.view(), NormalMode::kRotate, device, reference);
    EXPECT_TRUE(report.within_tolerance())
        << "level " << k << ": position " << report.max_position_error << ", normal "
        << report.max_normal_error;
  }
}

// The distance from p to the triangle abc, independently of the engine's: the
// projection onto the plane where it falls inside, else the nearest of the three edges.
double to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                   const glm::dvec3& c) {
  const auto to_segment = [&](const glm::dvec3& u, const glm::dvec3& w) {
    const glm::dvec3 d = w - u;
    const double t =
        glm::dot(d, d) > 0.0 ? std::clamp(glm::dot(p - u, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
    return glm::length(p - (u + t * d));
  };
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area2 = glm::dot(n, n);
  if (area2 > 0.0) {
    const glm::dvec3 q = p - glm::dot(p - a, n) / area2 * n;
    const double u = glm::dot(glm::cross(c - b, q - b), n),
                 v = glm::dot(glm::cross(a - c, q - c), n),
                 w = glm::dot(glm::cross(b - a, q - a), n);
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) return glm::length(p - q);
  }
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

double farthest(const std::vector<glm::dvec3>& points, const Mesh& mesh) {
  double worst = 0.0;
  for (const glm::dvec3& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      best = std::min(best, to_triangle(p, glm::dvec3(mesh.positions[mesh.indices[t]]),
                                        glm::dvec3(mesh.positions[mesh.indices[t + 1]]),
                                        glm::dvec3(mesh.positions[mesh.indices[t + 2]])));
    }
    worst = std::max(worst, best);
  }
  return worst;
}

// A level's error covers the distance between its surface and the full mesh's, both
// ways, measured here by brute force (the coarsest level: every triangle of the other).
TEST_P(BundledLevels, TheErrorCoversTheMeasuredDistanceBetweenTheSurfaces) {
  const RiggedMesh& full = model();
  const DetailLevels levels = make_detail_levels(full, LevelOptions{});
  const DetailLevel& coarsest = levels.level(levels.size() - 1);
  const Mesh& fine = levels.level(0).model.mesh();
  const Mesh& coarse = coarsest.model.mesh();
  std::vector<glm::dvec3> fine_points(fine.positions.begin(), fine.positions.end());
  std::vector<glm::dvec3> coarse_points;
  for (std::size_t t = 0; t + 2 < coarse.indices.size(); t += 3) {
    const glm::dvec3 a(coarse.positions[coarse.indices[t]]),
        b(coarse.positions[coarse.indices[t + 1]]), c(coarse.positions[coarse.indices[t + 2]]);
    coarse_points.push_back((a + b + c) / 3.0);
    coarse_points.push_back((a + b) / 2.0);
  }
  const double measured = std::max(farthest(fine_points, coarse), farthest(coarse_points, fine));
  std::printf("coarsest level: error %.4g, measured %.4g (mesh units)\n", coarsest.geometric_error,
              measured);
  EXPECT_GE(coarsest.geometric_error, measured * (1.0 - 1e-9));
  EXPECT_LT(coarsest.geometric_error, 2.0 * measured);  // and not far above it
}

// The frozen-fin level: the coarsest mesh again with only the body's stages, its error
// the coarsest's plus a bound that holds over swimming frames, its deformation on the
// device the reference's.
TEST_P(BundledLevels, FrozenFinsMoveNoFurtherThanTheirBoundAndDeformAsTheReference) {
  const RiggedMesh& full = model();
  const SwimModel swim(full);
  LevelOptions options;
  options.freeze_fins = true;
  options.value_bounds = swim.value_bounds();
  const DetailLevels levels = make_detail_levels(full, options);
  ASSERT_EQ(levels.size(), options.levels + 1);
  const DetailLevel& coarsest = levels.level(options.levels - 1);
  const DetailLevel& frozen = levels.level(options.levels);
  EXPECT_FALSE(coarsest.fins_frozen);
  EXPECT_TRUE(frozen.fins_frozen);
  EXPECT_EQ(frozen.vertex_count, coarsest.vertex_count);
  EXPECT_EQ(frozen.model.mesh().indices, coarsest.model.mesh().indices);
  const Rig& rig = frozen.model.rig();
  EXPECT_EQ(rig.components.front().chain.size(), full.rig().components.front().chain.size());
  for (std::size_t c = 1; c < rig.components.size(); ++c)
    EXPECT_TRUE(rig.components[c].chain.empty()) << rig.components[c].name;
  const double bound = frozen_fin_error(coarsest.model, options.value_bounds);
  EXPECT_GT(bound, 0.0);
  EXPECT_DOUBLE_EQ(frozen.geometric_error, coarsest.geometric_error + bound);
  // Swimming frames, slow (the pectoral fins beating) to fast, turning both ways.
  constexpr std::size_t kFish = 12;
  SwimReference fish(swim, std::vector<float>(kFish, 0.3f));
  std::vector<SwimInput> inputs(kFish);
  for (std::size_t i = 0; i < kFish; ++i) {
    inputs[i].speed = 0.05f * float(i);
    inputs[i].turn_rate = (i % 2 ? 1.0f : -1.0f) * 0.2f * float(i % 4);
  }
  double moved = 0.0;
  for (int frame = 0; frame < 24; ++frame) {
    fish.step(inputs, 1.0 / 24.0);
    const DeformedBatch<double> moving =
        run_reference(coarsest.model, fish.parameters(), NormalMode::kRotate);
    const DeformedBatch<double> still =
        run_reference(frozen.model, fish.parameters(), NormalMode::kRotate);
    for (std::size_t i = 0; i < kFish; ++i) {
      for (std::size_t v = 0; v < frozen.vertex_count; ++v)
        moved = std::max(moved, glm::length(moving.position(i, v) - still.position(i, v)));
    }
  }
  std::printf("frozen fins: moved %.4g, bound %.4g (mesh units)\n", moved, bound);
  EXPECT_GT(moved, 0.0);
  EXPECT_LE(moved, bound);
  // On the device, as the reference of its own rig.
  const RigParameters values = test::at_fractions_of_the_limits(full, {0.0, 0.45, -0.8, 1.0});
  ClDeformer deformer(test::shared_context(), frozen.model);
  const DeformedBatch<float> device = test::run_on_device(deformer, values, NormalMode::kRotate);
  const AccuracyReport report =
      compare_to_reference(frozen.model, values.view(), NormalMode::kRotate, device,
                           run_reference(frozen.model, values, NormalMode::kRotate));
  EXPECT_TRUE(report.within_tolerance())
      << "position " << report.max_position_error << ", normal " << report.max_normal_error;
}

INSTANTIATE_TEST_SUITE_P(DetailLevels, BundledLevels, ::testing::Values("blub", "barramundi"));

LevelOptions one_level() {
  LevelOptions options;
  options.levels = 1;
  return options;
}

std::string field_of(const RiggedMesh& model, const LevelOptions& options) {
  try {
    (void)make_detail_levels(model, options);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return e.field();
  }
  return "accepted";
}

TEST(DetailLevels, BadValueBoundsAreNamed) {
  LevelOptions options;
  options.freeze_fins = true;
  options.value_bounds = {0.1};
  EXPECT_EQ(field_of(blub(), options), "value_bounds");
  options.value_bounds = SwimModel(blub()).value_bounds();
  EXPECT_EQ(field_of(blub(), options), "accepted");
  for (double bad :
       {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.value_bounds[1] = bad;
    EXPECT_EQ(field_of(blub(), options), "value_bounds[1]") << bad;
  }
  // A rig with nothing below its root: no frozen level.
  const RiggedMesh bend =
      RiggedMesh::single_bend(blub().mesh(), find_body_frame(blub().mesh()), BendMode::kExact);
  LevelOptions two;
  two.levels = 2;
  two.freeze_fins = true;
  EXPECT_EQ(make_detail_levels(bend, two).size(), 2u);
}

TEST(DetailLevels, BadOptionsAndMeshesTooSmallAreNamed) {
  LevelOptions options;
  options.levels = 0;
  EXPECT_EQ(field_of(blub(), options), "levels");
  options.levels = kMaxDetailLevels + 1;
  EXPECT_EQ(field_of(blub(), options), "levels");
  options.levels = 1;
  EXPECT_EQ(field_of(blub(), options), "accepted");
  for (double ratio : {0.0, 1.0, -0.5, std::numeric_limits<double>::quiet_NaN()}) {
    options.triangle_ratio = ratio;
    EXPECT_EQ(field_of(blub(), options), "triangle_ratio") << ratio;
  }
  // A tetrahedron cannot lose triangles (a closed mesh of 4), nor can all-border meshes.
  Mesh tetrahedron;
  tetrahedron.positions = {{0, 0, 0}, {4, 0, 0}, {1, 1, 0}, {1, 0, 1.5f}};
  tetrahedron.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  compute_vertex_normals(tetrahedron);
  const RiggedMesh small =
      RiggedMesh::single_bend(tetrahedron, find_body_frame(tetrahedron), BendMode::kExact);
  EXPECT_EQ(field_of(small, LevelOptions{}), "levels");
  try {
    (void)make_detail_levels(small, LevelOptions{});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("level 1 keeps"), std::string::npos) << e.what();
  }
  const DetailLevels one = make_detail_levels(blub(), one_level());
  EXPECT_EQ(one.size(), 1u);
  EXPECT_EQ(field_of(blub(), one_level()), "accepted");
  try {
    (void)one.level(1);
    ADD_FAILURE() << "level 1 of 1";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "level");
  }
}

}  // namespace
}  // namespace finflex

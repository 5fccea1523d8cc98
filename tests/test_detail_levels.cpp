// Levels of detail (finflex/detail_levels.hpp) of the bundled fish: one vertex order
// whose prefixes are the levels, the rig carried over (fins stay fins), each level's
// deformation on the device against the double reference, and a kept vertex deformed
// exactly as the full mesh deforms it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
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

INSTANTIATE_TEST_SUITE_P(DetailLevels, BundledLevels, ::testing::Values("blub", "barramundi"));

std::string field_of(const RiggedMesh& model, const LevelOptions& options) {
  try {
    (void)make_detail_levels(model, options);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return e.field();
  }
  return "accepted";
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
  const DetailLevels one = make_detail_levels(blub(), LevelOptions{1, 0.25});
  EXPECT_EQ(one.size(), 1u);
  EXPECT_EQ(field_of(blub(), LevelOptions{1, 0.25}), "accepted");
  try {
    (void)one.level(1);
    ADD_FAILURE() << "level 1 of 1";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "level");
  }
}

}  // namespace
}  // namespace finflex

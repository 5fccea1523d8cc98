// Half-precision normals and tangents (NormalFormat::kHalf): 18 bytes per vertex
// instead of 24. Positions stay float32 and bit-identical; normals and tangents round
// to IEEE half, relative error 2^-11 per component, so unit vectors differ from the
// float32 ones by under 1e-3.
#include <gtest/gtest.h>

#include <cmath>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// Rounding to the nearest half moves a component by at most half a unit in the last
// place of the half: 2^(e - 11) for |value| in [2^e, 2^(e+1)), e >= -14, and 2^-25
// below (subnormal halves).
void expect_nearest_half(glm::vec3 full, glm::vec3 half, std::size_t vertex) {
  for (int c = 0; c < 3; ++c) {
    const float value = std::fabs(full[c]);
    const int exponent = value >= std::ldexp(1.0f, -14) ? std::ilogb(value) : -14;
    ASSERT_LE(std::fabs(full[c] - half[c]), std::ldexp(1.0f, exponent - 11))
        << "vertex " << vertex << " component " << c << ": " << full[c] << " -> " << half[c];
  }
}

template <typename Batch>
void expect_half_matches_float(const Batch& full, const Batch& half, std::size_t vertices,
                               std::size_t instances) {
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      ASSERT_EQ(full.position(i, v), half.position(i, v)) << "instance " << i << " vertex " << v;
      ASSERT_LT(glm::length(full.normal(i, v) - half.normal(i, v)), 1e-3f) << "vertex " << v;
      expect_nearest_half(full.normal(i, v), half.normal(i, v), v);
      if (full.layout.tangents) {
        ASSERT_LT(glm::length(full.tangent(i, v) - half.tangent(i, v)), 1e-3f) << "vertex " << v;
        expect_nearest_half(full.tangent(i, v), half.tangent(i, v), v);
      }
    }
  }
}

TEST(NormalFormat, LayoutBytesAndNames) {
  BatchLayout layout;
  EXPECT_EQ(layout.bytes_per_vertex(), 24u);
  layout.normal_format = NormalFormat::kHalf;
  EXPECT_EQ(layout.bytes_per_vertex(), 18u);
  layout.tangents = true;
  EXPECT_EQ(layout.bytes_per_vertex(), 24u);  // 12 + 6 + 6
  EXPECT_EQ(parse_normal_format("half"), NormalFormat::kHalf);
  EXPECT_EQ(parse_normal_format("float32"), NormalFormat::kFloat32);
  EXPECT_THROW(parse_normal_format("snorm8"), Error);
}

TEST(NormalFormat, HalfBendKeepsPositionsAndRoundsNormals) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));  // has tangents
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  ClDeformer deformer(test::shared_context(), model);
  const RigParameters m = test::values_of(model, {0.0f, 0.3f, -0.6f});
  DeviceBatch full = deformer.allocate(3);
  DeviceBatch half = deformer.allocate(3, NormalFormat::kHalf);
  EXPECT_EQ(half.layout.normal_format, NormalFormat::kHalf);
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    expect_half_matches_float(test::run_on_device(deformer, full, m, normals),
                              test::run_on_device(deformer, half, m, normals), mesh.vertex_count(),
                              3);
  }
}

TEST(NormalFormat, HalfRigOnBothPathsKeepsFloatIntermediates) {
  // Five passes: the intermediates ping-pong between two float32 scratch sets and only
  // the last pass rounds to half, so half and float32 outputs differ by one rounding.
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  ComponentSpec body;
  body.name = "body";
  for (const char* param : {"a", "b", "c", "d", "e"}) {
    StageSpec stage = make_stage(param[0] % 2 ? "bend" : "hinge", param);
    if (param[0] % 2 == 0) set_option(stage, "width", 0.2);
    body.chain.push_back(stage);
  }
  spec.components.push_back(body);
  const Mesh mesh = test::synthetic_fish(48, 24, true);
  const RiggedMesh model(mesh, resolve_rig(spec, mesh));
  ClDeformer deformer(test::shared_context(), model);
  ASSERT_EQ(deformer.pass_count(), 5u);
  RigParameters values(model, 2);
  values.set(0, "a", 0.4f);
  values.set(1, "b", -0.7f);
  values.set(1, "e", 0.5f);
  DeviceBatch full = deformer.allocate(2);
  DeviceBatch half = deformer.allocate(2, NormalFormat::kHalf);
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    expect_half_matches_float(
        test::run_on_device(deformer, full, values, NormalMode::kJacobian, path),
        test::run_on_device(deformer, half, values, NormalMode::kJacobian, path),
        mesh.vertex_count(), 2);
  }
}

}  // namespace
}  // namespace finflex

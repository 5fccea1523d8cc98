// The OpenCL backend (float32) against the double reference, on a synthetic fish and
// on every bundled real fish, for both bend modes, both normal modes and m across the
// whole valid range.
//
// Tolerances, and why:
//  - positions: 4e-6 * (|origin| + s_x). The kernels compute in float32 (unit
//    roundoff 6e-8) a handful of operations on coordinates of magnitude s_x, then add
//    the origin: a few ulps of |origin| + s_x, with margin.
//  - normals and tangents: 2e-5 (a few float ulps of a unit vector through rsqrt).
//  - Where the problem itself is ill-conditioned, float32 cannot do better than its
//    conditioning, so the bounds follow it:
//    * near the exact bend's range limit (1 - (2mx)^2 < 1e-3) the spine's slope
//      sqrt(1 - 4m^2x^2) has an infinite derivative: the float rounding of x alone
//      (1e-7 relative) moves the secant normal n by up to sqrt(2e-7) ~ 5e-4, so normals
//      get 2e-3 there and positions (p' = f + z n) 2e-3 |z| s_x more;
//    * Jacobian normals where the offset surface folds through itself (|1 - z k| <
//      0.05, METHOD.md section 6): the normal flips across the fold and is undefined on
//      it; and Jacobian normals near the exact bend's limit, where k = 2m / sqrt(1 - u^2)
//      inherits the 5e-4 uncertainty of the square root divided by a value that tends
//      to 0. These vertices are counted (under 1 %), not compared.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "finflex/body_frame.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/error.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/reference_deformer.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

struct MaxErrors {
  double position = 0.0;  // absolute error over the position bound, max (< 1 passes)
  double normal = 0.0;    // |difference| of unit vectors over its bound, max (< 1 passes)
  std::size_t folded = 0; // Jacobian normals on or near a fold, not compared
};

MaxErrors compare(const LocalMesh& local, const DeformedBatch<float>& device,
                  const DeformedBatch<double>& reference, const std::vector<float>& m,
                  const BendSettings& settings) {
  const BodyFrame& frame = local.frame;
  const double position_bound = 4e-6 * (glm::length(frame.origin) + frame.length);
  MaxErrors e;
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t v = 0; v < local.vertex_count(); ++v) {
      const glm::dvec3& p = local.positions[v];
      const double u = 2.0 * m[i] * p.x;
      const bool near_limit = settings.mode == BendMode::kExact && 1.0 - u * u < 1e-3;
      const double c = std::sqrt(std::max(1.0 - u * u, 0.0));
      const double curvature = settings.mode == BendMode::kExact
                                   ? 2.0 * m[i] / std::max(c, 1e-6)
                                   : 2.0 * m[i];  // the series stays below 4 m: no fold on a fish
      const bool folded = settings.normals == NormalMode::kJacobian &&
                          (near_limit || std::fabs(1.0 - p.z * curvature) < 0.05);

      const double position_error =
          glm::length(glm::dvec3(device.position(i, v)) - reference.position(i, v));
      const double bound =
          position_bound + (near_limit ? 2e-3 * std::fabs(p.z) * frame.length : 0.0);
      e.position = std::max(e.position, position_error / bound);
      if (folded) {
        ++e.folded;
        continue;
      }
      double normal_error = glm::length(glm::dvec3(device.normal(i, v)) - reference.normal(i, v));
      if (local.has_tangents()) {
        normal_error = std::max(
            normal_error, glm::length(glm::dvec3(device.tangent(i, v)) - reference.tangent(i, v)));
      }
      e.normal = std::max(e.normal, normal_error / (near_limit ? 2e-3 : 2e-5));
    }
  }
  return e;
}

// m at fractions of the limit, both signs, the limit itself included.
std::vector<float> parameter_sweep(double x_max) {
  const double limit = max_abs_m(x_max);
  std::vector<float> m;
  for (double f : {0.0, 0.1, -0.35, 0.6, -0.85, 1.0, -1.0}) m.push_back(static_cast<float>(f * limit));
  return m;
}

void expect_matches_reference(const Mesh& mesh, const BodyFrame& frame, const std::string& name) {
  const LocalMesh local = make_local_mesh(mesh, frame);
  const std::vector<float> m = parameter_sweep(local.x_max);
  ClDeformer deformer(test::shared_context(), local);
  const ReferenceDeformer reference(local);
  DeviceBatch batch = deformer.allocate(m.size());
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      const BendSettings settings{mode, normals};
      deformer.enqueue(m, settings, batch, /*clamp=*/true);
      const MaxErrors e =
          compare(local, deformer.read(batch), reference.run(m, settings, true), m, settings);
      SCOPED_TRACE(name + " " + to_string(mode) + " " + to_string(normals));
      EXPECT_LT(e.position, 1.0);
      EXPECT_LT(e.normal, 1.0);
      // Folds only appear at the ends of the spine near the range limit.
      EXPECT_LT(e.folded, local.vertex_count() * m.size() / 100);
    }
  }
}

TEST(ClDeformer, MatchesReferenceOnSyntheticFish) {
  expect_matches_reference(test::synthetic_fish(64, 48, true), BodyFrame::identity(), "synthetic");
}

TEST(ClDeformer, MatchesReferenceOnSyntheticFishInAnOffsetFrame) {
  BodyFrame frame;
  frame.origin = {3.0, -1.0, 2.0};
  frame.axis_x = glm::normalize(glm::dvec3(1.0, 1.0, 0.0));
  frame.axis_y = glm::normalize(glm::dvec3(-1.0, 1.0, 0.0));
  frame.axis_z = glm::cross(frame.axis_x, frame.axis_y);
  frame.length = 2.5;
  Mesh mesh = test::synthetic_fish(32, 24, true);
  for (glm::vec3& p : mesh.positions) p = glm::vec3(frame.point_to_mesh(glm::dvec3(p)));
  for (glm::vec3& n : mesh.normals) n = glm::vec3(frame.vector_to_mesh(glm::dvec3(n)));
  for (glm::vec4& t : mesh.tangents) t = glm::vec4(glm::vec3(frame.vector_to_mesh(glm::dvec3(t))), t.w);
  expect_matches_reference(mesh, frame, "offset synthetic");
}

TEST(ClDeformer, MatchesReferenceOnEveryBundledFish) {
  for (const char* fish : test::kBundledFish) {
    const Mesh mesh = load_mesh(test::data_path(fish));
    expect_matches_reference(mesh, find_body_frame(mesh), fish);
  }
}

TEST(ClDeformer, ZeroParameterIsTheIdentity) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer(test::shared_context(), local);
  DeviceBatch batch = deformer.allocate(1);
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      deformer.enqueue({0.0f}, {mode, normals}, batch);
      const DeformedBatch<float> out = deformer.read(batch);
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        EXPECT_LT(glm::length(out.position(0, v) - mesh.positions[v]), 2e-6f);
        EXPECT_LT(glm::length(out.normal(0, v) - glm::normalize(mesh.normals[v])), 2e-6f);
      }
    }
  }
}

TEST(ClDeformer, BatchEqualsSingleRuns) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer(test::shared_context(), local);
  const std::size_t instances = 1000;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> m(instances);
  for (float& value : m) value = uniform(random) * static_cast<float>(max_abs_m(local.x_max));
  const BendSettings settings{BendMode::kExact, NormalMode::kJacobian};

  DeviceBatch batch = deformer.allocate(instances);
  deformer.enqueue(m, settings, batch);
  const DeformedBatch<float> all = deformer.read(batch);

  DeviceBatch single = deformer.allocate(1);
  for (std::size_t i = 0; i < instances; ++i) {
    deformer.enqueue({m[i]}, settings, single);
    const DeformedBatch<float> one = deformer.read(single);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      ASSERT_EQ(one.position(0, v), all.position(i, v)) << "instance " << i << " vertex " << v;
      ASSERT_EQ(one.normal(0, v), all.normal(i, v)) << "instance " << i << " vertex " << v;
    }
  }
}

TEST(ClDeformer, RejectsBadInputsBeforeLaunching) {
  const LocalMesh local = make_local_mesh(test::synthetic_fish(8, 8), BodyFrame::identity());
  ClDeformer deformer(test::shared_context(), local);
  EXPECT_THROW(deformer.allocate(0), Error);
  DeviceBatch batch = deformer.allocate(2);
  const BendSettings settings;
  EXPECT_THROW(deformer.enqueue({0.1f}, settings, batch), Error);  // wrong count
  EXPECT_THROW(deformer.enqueue({0.1f, NAN}, settings, batch), Error);
  try {
    deformer.enqueue({0.1f, -1.01f}, settings, batch);
    FAIL() << "expected an out-of-range error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutOfRange);
    EXPECT_EQ(e.field(), "m[1]");
  }
  try {
    deformer.allocate(std::size_t(1) << 40);
    FAIL() << "expected an allocation error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "instances");
  }
}

}  // namespace
}  // namespace finflex

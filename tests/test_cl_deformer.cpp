// The OpenCL backend (float32) against the double reference, on a synthetic fish and
// on every bundled real fish, for both bend modes, both normal modes and m across the
// whole valid range.
//
// Tolerances: those of finflex/accuracy.hpp (and docs/accuracy.md): a few float32
// ulps where the bend is well conditioned, bounds that follow the conditioning near
// the exact bend's range limit, and ill-defined Jacobian normals on folds skipped.
#include <cmath>
#include <cstddef>
#include <random>

#include <gtest/gtest.h>

#include "finflex/accuracy.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/error.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/reference_deformer.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// m at fractions of the limit, both signs, the limit itself included.
std::vector<float> parameter_sweep(double x_max) {
  const double limit = max_abs_m(x_max);
  std::vector<float> m;
  for (double f : {0.0, 0.1, -0.35, 0.6, -0.85, 1.0, -1.0})
    m.push_back(static_cast<float>(f * limit));
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
      const AccuracyReport report =
          compare_to_reference(local, checked_bend_params(m, local.x_max, true), settings,
                               deformer.read(batch), reference.run(m, settings, true));
      SCOPED_TRACE(name + " " + to_string(mode) + " " + to_string(normals));
      EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
      EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
      // Ill-defined normals only appear at the ends of the spine near the range limit.
      EXPECT_LT(report.skipped_normals, local.vertex_count() * m.size() / 100);
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
  for (glm::vec4& t : mesh.tangents)
    t = glm::vec4(glm::vec3(frame.vector_to_mesh(glm::dvec3(t))), t.w);
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

// The low-resolution Blub with its own body frame and a deformer: several tests' set-up.
struct SmallFish {
  Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer{test::shared_context(), local};
  float limit = static_cast<float>(max_abs_m(local.x_max));
};

TEST(ClDeformer, BatchEqualsSingleRuns) {
  SmallFish fish;
  const Mesh& mesh = fish.mesh;
  const LocalMesh& local = fish.local;
  ClDeformer& deformer = fish.deformer;
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

// Kernel arguments are set only when a frame goes to another batch than the last one:
// alternating batches of different sizes must each get their own frames.
TEST(ClDeformer, AlternatingBatchesEachGetTheirOwnFrames) {
  SmallFish fish;
  ClDeformer& deformer = fish.deformer;
  const float limit = fish.limit;
  const BendSettings settings{BendMode::kPaper, NormalMode::kRotate};
  DeviceBatch two = deformer.allocate(2);
  DeviceBatch three = deformer.allocate(3);
  ASSERT_NE(two.serial, three.serial);
  DeviceBatch single = deformer.allocate(1);
  auto expect_instance = [&](const DeformedBatch<float>& batch, std::size_t i, float m) {
    deformer.enqueue({m}, settings, single);
    const DeformedBatch<float> one = deformer.read(single);
    for (std::size_t v = 0; v < fish.mesh.vertex_count(); ++v)
      ASSERT_EQ(one.position(0, v), batch.position(i, v)) << "m " << m << " vertex " << v;
  };
  deformer.enqueue({0.1f * limit, 0.2f * limit}, settings, two);
  deformer.enqueue({0.3f * limit, 0.4f * limit, 0.5f * limit}, settings, three);
  deformer.enqueue({-0.6f * limit, -0.7f * limit}, settings, two);  // back to the first
  const DeformedBatch<float> from_two = deformer.read(two);
  const DeformedBatch<float> from_three = deformer.read(three);
  expect_instance(from_two, 0, -0.6f * limit);
  expect_instance(from_two, 1, -0.7f * limit);
  expect_instance(from_three, 2, 0.5f * limit);
}

// Frames enqueued back to back without waiting: each upload reads its own staging
// slot (a ring of DeviceBatch::kStagingSlots), so the last frame's values win and the
// earlier ones were each deformed with their own.
TEST(ClDeformer, FramesInFlightKeepTheirOwnParameters) {
  SmallFish fish;
  ClDeformer& deformer = fish.deformer;
  const float limit = fish.limit;
  const BendSettings settings{BendMode::kExact, NormalMode::kRotate};
  DeviceBatch batch = deformer.allocate(2);
  DeviceBatch copy = deformer.allocate(2);
  for (int f = 0; f < 7; ++f) {
    deformer.enqueue({0.1f * float(f) * limit, -0.12f * float(f) * limit}, settings, batch);
    // Copy frame f's outputs aside on the queue, to compare with a lone run of it.
    if (f == 4) {
      const std::size_t bytes = batch.layout.attribute_elements() * sizeof(float);
      check_cl(test::shared_context().queue().enqueueCopyBuffer(batch.positions, copy.positions, 0,
                                                                0, bytes),
               "clEnqueueCopyBuffer");
    }
  }
  const DeformedBatch<float> last = deformer.read(batch);
  const DeformedBatch<float> fourth = deformer.read(copy);  // positions only
  DeviceBatch alone = deformer.allocate(2);
  for (int f : {4, 6}) {
    deformer.enqueue({0.1f * float(f) * limit, -0.12f * float(f) * limit}, settings, alone);
    const DeformedBatch<float> expected = deformer.read(alone);
    const DeformedBatch<float>& got = f == 4 ? fourth : last;
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t v = 0; v < fish.mesh.vertex_count(); ++v)
        ASSERT_EQ(got.position(i, v), expected.position(i, v)) << "frame " << f << " vertex " << v;
    }
  }
}

TEST(ClDeformer, SeveralInstancesPerWorkItemGiveTheSameResult) {
  // GPUs take 2 instances per work-item; every count, odd batches included, must give
  // what one instance per work-item gives (to float32 rounding: the compiler may
  // contract multiply-adds differently in the two kernel shapes).
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  std::vector<float> m;
  for (int i = 0; i < 7; ++i) m.push_back(static_cast<float>(0.1 * i * max_abs_m(local.x_max)));
  const BendSettings settings{BendMode::kExact, NormalMode::kJacobian};
  ClDeformer one(test::shared_context(), local, 1);
  DeviceBatch reference_batch = one.allocate(m.size());
  one.enqueue(m, settings, reference_batch);
  const DeformedBatch<float> expected = one.read(reference_batch);
  const double bound = 4e-6 * (glm::length(local.frame.origin) + local.frame.length);
  for (std::size_t per_item : {2u, 3u, 8u}) {
    ClDeformer several(test::shared_context(), local, per_item);
    DeviceBatch batch = several.allocate(m.size());
    several.enqueue(m, settings, batch);
    const DeformedBatch<float> got = several.read(batch);
    for (std::size_t i = 0; i < m.size(); ++i) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        ASSERT_LT(glm::length(got.position(i, v) - expected.position(i, v)), bound)
            << per_item << " per item, instance " << i << " vertex " << v;
        ASSERT_LT(glm::length(got.normal(i, v) - expected.normal(i, v)), 2e-6f);
        ASSERT_LT(glm::length(got.tangent(i, v) - expected.tangent(i, v)), 2e-6f);
      }
    }
  }
}

TEST(ClDeformer, FourThousandInstancesOfTheFullFish) {
  // 4,000 x 10,786 vertices: 2 x 519 MB of float32 outputs in one launch.
  const Mesh mesh = load_mesh(test::data_path("blub/fish.obj"));
  const LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
  ClDeformer deformer(test::shared_context(), local);
  const std::size_t instances = 4000;
  std::vector<float> m(instances);
  for (std::size_t i = 0; i < instances; ++i) {
    m[i] = static_cast<float>(max_abs_m(local.x_max) * std::sin(0.01 * static_cast<double>(i)));
  }
  DeviceBatch batch = deformer.allocate(instances);
  const BendSettings settings{BendMode::kPaper, NormalMode::kRotate};
  deformer.enqueue(m, settings, batch);
  const DeformedBatch<float> all = deformer.read(batch);
  // Spot-check instances across the whole batch against the reference.
  const std::vector<std::size_t> checked = {0, 1, 777, 2048, 3999};
  std::vector<float> checked_m;
  for (std::size_t i : checked) checked_m.push_back(m[i]);
  const DeformedBatch<double> reference = ReferenceDeformer(local).run(checked_m, settings);
  const double bound = 4e-6 * (glm::length(local.frame.origin) + local.frame.length);
  for (std::size_t k = 0; k < checked.size(); ++k) {
    for (std::size_t v = 0; v < local.vertex_count(); v += 7) {
      ASSERT_LT(glm::length(glm::dvec3(all.position(checked[k], v)) - reference.position(k, v)),
                bound)
          << "instance " << checked[k] << " vertex " << v;
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

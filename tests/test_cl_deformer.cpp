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

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// m at fractions of the limit, both signs, the limit itself included.
const std::vector<double> kSweep = {0.0, 0.1, -0.35, 0.6, -0.85, 1.0, -1.0};

void expect_matches_reference(const Mesh& mesh, const BodyFrame& frame, const std::string& name) {
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    const RiggedMesh model = RiggedMesh::single_bend(mesh, frame, mode);
    ClDeformer deformer(test::shared_context(), model);
    ASSERT_TRUE(deformer.uses_single_bend_kernel());
    const RigParameters m = test::bend_fractions(model, kSweep);
    std::vector<float> used(m.values().size());  // the limits, clamped as the backends do
    check_parameters(model.rig(), m.view(), /*clamp=*/true, used.data());
    const RigParameters checked = test::values_of(model, used);
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      const AccuracyReport report =
          compare_to_reference(model, checked.view(), normals,
                               test::run_on_device(deformer, m, normals, RigPath::kAuto, true),
                               run_reference(model, m, normals, true));
      SCOPED_TRACE(name + " " + to_string(mode) + " " + to_string(normals));
      EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
      EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
      // Ill-defined normals only appear at the ends of the spine near the range limit.
      EXPECT_LT(report.skipped_normals, mesh.vertex_count() * kSweep.size() / 100);
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
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), mode);
    ClDeformer deformer(test::shared_context(), model);
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      const DeformedBatch<float> out =
          test::run_on_device(deformer, test::values_of(model, {0.0f}), normals);
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
  RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  ClDeformer deformer{test::shared_context(), model};
  float limit = static_cast<float>(test::bend_limit(model));

  RigParameters m(const std::vector<float>& values) const { return test::values_of(model, values); }
};

TEST(ClDeformer, BatchEqualsSingleRuns) {
  SmallFish fish;
  const std::size_t instances = 1000;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> m(instances);
  for (float& value : m) value = uniform(random) * fish.limit;
  const NormalMode normals = NormalMode::kJacobian;
  const DeformedBatch<float> all = test::run_on_device(fish.deformer, fish.m(m), normals);

  DeviceBatch single = fish.deformer.allocate(1);
  for (std::size_t i = 0; i < instances; ++i) {
    const DeformedBatch<float> one =
        test::run_on_device(fish.deformer, single, fish.m({m[i]}), normals);
    for (std::size_t v = 0; v < fish.mesh.vertex_count(); ++v) {
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
  const NormalMode normals = NormalMode::kRotate;
  DeviceBatch two = deformer.allocate(2);
  DeviceBatch three = deformer.allocate(3);
  ASSERT_NE(two.serial, three.serial);
  DeviceBatch single = deformer.allocate(1);
  auto expect_instance = [&](const DeformedBatch<float>& batch, std::size_t i, float m) {
    const DeformedBatch<float> one = test::run_on_device(deformer, single, fish.m({m}), normals);
    for (std::size_t v = 0; v < fish.mesh.vertex_count(); ++v)
      ASSERT_EQ(one.position(0, v), batch.position(i, v)) << "m " << m << " vertex " << v;
  };
  auto enqueue = [&](DeviceBatch& batch, const RigParameters& m) {
    ClJob job;
    job.model = &fish.model;
    job.parameters = m.view();
    job.normals = normals;
    job.outputs = &batch;
    deformer.enqueue(job);
  };
  enqueue(two, fish.m({0.1f * limit, 0.2f * limit}));
  enqueue(three, fish.m({0.3f * limit, 0.4f * limit, 0.5f * limit}));
  enqueue(two, fish.m({-0.6f * limit, -0.7f * limit}));  // back to the first
  const DeformedBatch<float> from_two = deformer.read(two);
  const DeformedBatch<float> from_three = deformer.read(three);
  expect_instance(from_two, 0, -0.6f * limit);
  expect_instance(from_two, 1, -0.7f * limit);
  expect_instance(from_three, 2, 0.5f * limit);
}

// Frames enqueued back to back without waiting: each upload reads its own staging
// slot (a ring of three), so the last frame's values win and the earlier ones were
// each deformed with their own.
TEST(ClDeformer, FramesInFlightKeepTheirOwnParameters) {
  SmallFish fish;
  ClDeformer& deformer = fish.deformer;
  const float limit = fish.limit;
  const NormalMode normals = NormalMode::kRotate;
  DeviceBatch batch = deformer.allocate(2);
  DeviceBatch copy = deformer.allocate(2);
  auto frame_values = [&](int f) {
    return fish.m({0.1f * float(f) * limit, -0.12f * float(f) * limit});
  };
  for (int f = 0; f < 7; ++f) {
    const RigParameters m = frame_values(f);  // gone before the frame runs
    ClJob job;
    job.model = &fish.model;
    job.parameters = m.view();
    job.normals = normals;
    job.outputs = &batch;
    deformer.enqueue(job);
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
    const DeformedBatch<float> expected =
        test::run_on_device(deformer, alone, frame_values(f), normals);
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
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  std::vector<double> fractions;
  for (int i = 0; i < 7; ++i) fractions.push_back(0.1 * i);
  const RigParameters m = test::bend_fractions(model, fractions);
  const NormalMode normals = NormalMode::kJacobian;
  ClOptions one_per_item;
  one_per_item.instances_per_item = 1;
  ClDeformer one(test::shared_context(), model, one_per_item);
  const DeformedBatch<float> expected = test::run_on_device(one, m, normals);
  const BodyFrame& frame = model.rig().components[0].frame;
  const double bound = 4e-6 * (glm::length(frame.origin) + frame.length);
  for (std::size_t per_item : {2u, 3u, 8u}) {
    ClOptions options;
    options.instances_per_item = per_item;
    ClDeformer several(test::shared_context(), model, options);
    const DeformedBatch<float> got = test::run_on_device(several, m, normals);
    for (std::size_t i = 0; i < fractions.size(); ++i) {
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
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  ClDeformer deformer(test::shared_context(), model);
  const std::size_t instances = 4000;
  std::vector<float> m(instances);
  for (std::size_t i = 0; i < instances; ++i) {
    m[i] = static_cast<float>(test::bend_limit(model) * std::sin(0.01 * static_cast<double>(i)));
  }
  const NormalMode normals = NormalMode::kRotate;
  const DeformedBatch<float> all =
      test::run_on_device(deformer, test::values_of(model, m), normals);
  // Spot-check instances across the whole batch against the reference.
  const std::vector<std::size_t> checked = {0, 1, 777, 2048, 3999};
  std::vector<float> checked_m;
  for (std::size_t i : checked) checked_m.push_back(m[i]);
  const DeformedBatch<double> reference =
      run_reference(model, test::values_of(model, checked_m), normals);
  const BodyFrame& frame = model.rig().components[0].frame;
  const double bound = 4e-6 * (glm::length(frame.origin) + frame.length);
  for (std::size_t k = 0; k < checked.size(); ++k) {
    for (std::size_t v = 0; v < mesh.vertex_count(); v += 7) {
      ASSERT_LT(glm::length(glm::dvec3(all.position(checked[k], v)) - reference.position(k, v)),
                bound)
          << "instance " << checked[k] << " vertex " << v;
    }
  }
}

TEST(ClDeformer, RejectsBadInputsBeforeLaunching) {
  const RiggedMesh model =
      RiggedMesh::single_bend(test::synthetic_fish(8, 8), BodyFrame::identity(), BendMode::kPaper);
  ClDeformer deformer(test::shared_context(), model);
  EXPECT_THROW(deformer.allocate(0), Error);
  DeviceBatch batch = deformer.allocate(2);
  const NormalMode normals = NormalMode::kRotate;
  EXPECT_THROW(test::run_on_device(deformer, batch, test::values_of(model, {0.1f}), normals),
               Error);  // wrong count
  EXPECT_THROW(test::run_on_device(deformer, batch, test::values_of(model, {0.1f, NAN}), normals),
               Error);
  try {
    test::run_on_device(deformer, batch, test::values_of(model, {0.1f, -1.01f}), normals);
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

// Outputs that do not fit the model (another mesh's, with or without tangents, or
// buffers smaller than their layout says) are refused before anything is written.
TEST(ClDeformer, OutputsOfAnotherModelAreRefused) {
  const RiggedMesh small =
      RiggedMesh::single_bend(test::synthetic_fish(8, 8), BodyFrame::identity(), BendMode::kPaper);
  const RiggedMesh large = RiggedMesh::single_bend(test::synthetic_fish(32, 24, true),
                                                   BodyFrame::identity(), BendMode::kPaper);
  ClDeformer small_deformer(test::shared_context(), small);
  ClDeformer large_deformer(test::shared_context(), large);
  DeviceBatch small_batch = small_deformer.allocate(2);
  const RigParameters m = test::values_of(large, {0.1f, 0.2f});
  auto field_of = [&](const ClJob& job) -> std::string {
    try {
      large_deformer.enqueue(job);
    } catch (const Error& e) {
      return e.field();
    }
    return "accepted";
  };
  ClJob job;
  job.model = &large;
  job.parameters = m.view();
  job.outputs = &small_batch;  // fewer slots, no tangents
  EXPECT_EQ(field_of(job), "job.outputs");
  // The layout of the right model, but buffers of the small one.
  DeviceBatch forged = large_deformer.allocate(2);
  forged.positions = small_batch.positions;
  forged.serial = small_batch.serial + 1000000;
  job.outputs = &forged;
  EXPECT_EQ(field_of(job), "job.outputs");
  // Another model in the job.
  DeviceBatch right = large_deformer.allocate(2);
  job.outputs = &right;
  job.model = &small;
  EXPECT_EQ(field_of(job), "job.model");
  job.model = &large;
  EXPECT_EQ(field_of(job), "accepted");
}

}  // namespace
}  // namespace finflex

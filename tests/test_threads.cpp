// Threads, as the thread-safety rules of the public headers allow them: several
// deformers on one Context, one deformer shared by several threads (each with its own
// batch and parameters), RigFrames sharing a deformer, the reference from several
// threads. Every frame is compared bit for bit with the same frame computed by one
// thread alone. Also run under ThreadSanitizer in CI.
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

constexpr std::size_t kThreads = 4;
constexpr std::size_t kFrames = 24;
constexpr std::size_t kInstances = 6;

const RiggedMesh& fish() {
  static const RiggedMesh model = [] {
    const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
    return RiggedMesh(
        mesh,
        resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), mesh));
  }();
  return model;
}

// Thread t's parameters at frame f: every parameter a different fraction of its limit.
RigParameters values_at(const RiggedMesh& model, std::size_t t, std::size_t f) {
  RigParameters values(model, kInstances);
  for (std::size_t i = 0; i < kInstances; ++i) {
    for (const RigParameter& p : model.rig().parameters) {
      const double phase = 0.37 * double(t) + 0.11 * double(f) + 0.05 * double(i + p.offset);
      values.values()[i * values.values_per_instance() + p.offset] =
          static_cast<float>(p.limit * 0.9 * std::sin(3.0 * phase));
    }
  }
  return values;
}

bool same_bits(const DeformedBatch<float>& a, const DeformedBatch<float>& b) {
  auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0);
  };
  return same(a.positions, b.positions) && same(a.normals, b.normals) &&
         same(a.tangents, b.tangents);
}

ClJob job_for(const RigParameters& values, DeviceBatch& batch, RigPath path) {
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = NormalMode::kJacobian;
  job.path = path;
  job.outputs = &batch;
  return job;
}

// expected[t][f]: thread t's frame f, computed by one thread on its own deformer.
std::vector<std::vector<DeformedBatch<float>>> expected_frames(RigPath path) {
  ClDeformer deformer(test::shared_context(), fish());
  DeviceBatch batch = deformer.allocate(kInstances);
  std::vector<std::vector<DeformedBatch<float>>> expected(kThreads);
  for (std::size_t t = 0; t < kThreads; ++t) {
    for (std::size_t f = 0; f < kFrames; ++f) {
      const RigParameters values = values_at(fish(), t, f);
      deformer.enqueue(job_for(values, batch, path));
      expected[t].push_back(deformer.read(batch));
    }
  }
  return expected;
}

// Runs `body(t, mismatches)` on kThreads threads; returns the mismatching frames.
template <typename Body>
std::size_t run_threads(Body body) {
  std::vector<std::size_t> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      try {
        body(t, mismatches[t]);
      } catch (const std::exception& e) {
        ADD_FAILURE() << "thread " << t << ": " << e.what();
        ++mismatches[t];
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  std::size_t total = 0;
  for (const std::size_t m : mismatches) total += m;
  return total;
}

TEST(Threads, SeveralDeformersOnOneContextEachOnItsOwnThread) {
  for (const RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    const auto expected = expected_frames(path);
    const std::size_t mismatches = run_threads([&](std::size_t t, std::size_t& bad) {
      ClDeformer deformer(test::shared_context(), fish());
      DeviceBatch batch = deformer.allocate(kInstances);
      for (std::size_t f = 0; f < kFrames; ++f) {
        const RigParameters values = values_at(fish(), t, f);
        deformer.enqueue(job_for(values, batch, path));
        bad += !same_bits(deformer.read(batch), expected[t][f]);
      }
    });
    EXPECT_EQ(mismatches, 0u) << to_string(path);
  }
}

TEST(Threads, OneDeformerSharedByThreadsEachWithItsOwnBatch) {
  for (const RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    const auto expected = expected_frames(path);
    ClDeformer shared(test::shared_context(), fish());
    const std::size_t mismatches = run_threads([&](std::size_t t, std::size_t& bad) {
      DeviceBatch batch = shared.allocate(kInstances);
      for (std::size_t f = 0; f < kFrames; ++f) {
        const RigParameters values = values_at(fish(), t, f);
        shared.enqueue(job_for(values, batch, path));
        bad += !same_bits(shared.read(batch), expected[t][f]);
      }
    });
    EXPECT_EQ(mismatches, 0u) << to_string(path);
  }
}

TEST(Threads, RigFramesOnSeveralThreadsSharingADeformer) {
  const auto expected = expected_frames(RigPath::kFused);
  ClDeformer shared(test::shared_context(), fish());
  const std::size_t mismatches = run_threads([&](std::size_t t, std::size_t& bad) {
    RigFrame frame;
    frame.add(shared, kInstances);
    for (std::size_t f = 0; f < kFrames; ++f) {
      frame.parameters(0).values() = values_at(fish(), t, f).values();
      frame.enqueue(NormalMode::kJacobian, RigPath::kFused);
      bad += !same_bits(shared.read(frame.batch(0)), expected[t][f]);
    }
  });
  EXPECT_EQ(mismatches, 0u);
}

TEST(Threads, TheReferenceRunsOnSeveralThreadsOnOneModel) {
  std::vector<DeformedBatch<double>> expected;
  for (std::size_t t = 0; t < kThreads; ++t) {
    expected.push_back(run_reference(fish(), values_at(fish(), t, 0), NormalMode::kJacobian));
  }
  const std::size_t mismatches = run_threads([&](std::size_t t, std::size_t& bad) {
    for (int k = 0; k < 3; ++k) {
      const DeformedBatch<double> out =
          run_reference(fish(), values_at(fish(), t, 0), NormalMode::kJacobian);
      bad += out.positions != expected[t].positions || out.normals != expected[t].normals;
    }
  });
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace finflex

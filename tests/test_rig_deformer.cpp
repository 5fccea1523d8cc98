// Rigged deformation: the fused and multi-pass OpenCL paths against each other and
// against the CPU reference that applies the chains literally (METHOD.md section 2),
// on every shipped rig and on deep and long synthetic rigs.
//
// Tolerances, and why:
//  - fused vs passes: the same float32 operations in the same order, the passes only
//    storing intermediate float32 values: 1e-6 (|origin| + s_x) for positions, 1e-5 for
//    normals (the compilers may contract a multiply-add differently per kernel);
//  - against the double reference: every stage adds a few float32 ulps, so the
//    single-bend bounds (finflex/accuracy.hpp) times the length of the longest path.
//    Parameters stay below 0.8 of their limits, away from the exact bend's
//    ill-conditioned end and from folds.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

StageSpec bend(const std::string& param, BendMode mode = BendMode::kExact) {
  StageSpec s = make_stage("bend", param);
  set_option(s, "mode", to_string(mode));
  return s;
}

StageSpec hinge(const std::string& param, double width) {
  StageSpec s = make_stage("hinge", param);
  set_option(s, "width", width);
  return s;
}

ComponentSpec box_component(const std::string& name, const std::string& parent, glm::dvec3 min,
                            glm::dvec3 max, std::vector<StageSpec> chain) {
  ComponentSpec c;
  c.name = name;
  c.parent = parent;
  c.select.kind = SelectorSpec::Kind::kBox;
  c.select.box_min = min;
  c.select.box_max = max;
  c.chain = std::move(chain);
  return c;
}

ComponentSpec root(std::vector<StageSpec> chain) {
  ComponentSpec c;
  c.name = "body";
  c.chain = std::move(chain);
  return c;
}

// A tail cut four times: body > tail1 > tail2 > tail3 > tail4, each with its own stage,
// boxes in the parent's local frame (each child's auto frame starts at its cut).
RigSpec deep_tail_rig() {
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  spec.components.push_back(root({bend("body_m")}));
  const double big = 10.0;
  std::string parent = "body";
  for (int level = 1; level <= 4; ++level) {
    const std::string name = "tail" + std::to_string(level);
    // Each auto child frame has x pointing tailwards from its cut, length its extent:
    // the next cut is at 40 % of it.
    const double cut = level == 1 ? -0.1 : 0.4;
    const glm::dvec3 min = level == 1 ? glm::dvec3(-big) : glm::dvec3(cut, -big, -big);
    const glm::dvec3 max = level == 1 ? glm::dvec3(cut, big, big) : glm::dvec3(big);
    spec.components.push_back(box_component(
        name, parent, min, max,
        {level % 2 ? hinge(name + "_angle", 0.3) : bend(name + "_m", BendMode::kPaper)}));
    parent = name;
  }
  return spec;
}

// One component with a chain of five stages.
RigSpec long_chain_rig() {
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  spec.components.push_back(
      root({bend("a"), hinge("b", 0.2), bend("c", BendMode::kPaper), hinge("d", 0.0), bend("e")}));
  return spec;
}

// Random parameters within `fraction` of each one's limit.
RigParameters random_parameters(const Rig& rig, std::size_t instances, double fraction,
                                unsigned seed) {
  RigParameters values(rig, instances);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-fraction, fraction);
  for (std::size_t i = 0; i < instances; ++i) {
    for (const RigParameter& parameter : rig.parameters) {
      for (std::size_t k = 0; k < parameter.count; ++k) {
        values.values()[i * values.values_per_instance() + parameter.offset + k] =
            static_cast<float>(uniform(random) * parameter.limit);
      }
    }
  }
  return values;
}

// The generic rig kernels (not the single-bend one), dispatched as `dispatch` says.
ClOptions rig_kernels(RigDispatch dispatch = RigDispatch::kAuto, std::size_t per_item = 0) {
  ClOptions options;
  options.dispatch = dispatch;
  options.instances_per_item = per_item;
  options.single_bend_kernel = false;
  return options;
}

struct Difference {
  double position = 0.0;
  double normal = 0.0;
};

template <typename A, typename B>
Difference max_difference(const A& a, const B& b, std::size_t vertices, std::size_t instances) {
  Difference d;
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      d.position = std::max(
          d.position, glm::length(glm::dvec3(a.position(i, v)) - glm::dvec3(b.position(i, v))));
      d.normal =
          std::max(d.normal, glm::length(glm::dvec3(a.normal(i, v)) - glm::dvec3(b.normal(i, v))));
      if (a.layout.tangents) {
        d.normal = std::max(d.normal,
                            glm::length(glm::dvec3(a.tangent(i, v)) - glm::dvec3(b.tangent(i, v))));
      }
    }
  }
  return d;
}

// Scale of the coordinates the kernels handle: the root frame's origin and length.
double coordinate_scale(const Rig& rig) {
  const BodyFrame& f = rig.components.front().frame;
  return glm::length(f.origin) + f.length;
}

void expect_paths_agree_with_each_other_and_the_reference(const Mesh& mesh, const Rig& rig,
                                                          const std::string& name,
                                                          RigDispatch dispatch) {
  const RiggedMesh model(mesh, rig);
  ClDeformer deformer(test::shared_context(), model, rig_kernels(dispatch));
  const std::size_t instances = 5;
  const RigParameters values = random_parameters(rig, instances, 0.8, 11);
  DeviceBatch batch = deformer.allocate(instances);
  const std::size_t longest = std::max<std::size_t>(model.longest_path(), 1);
  const double scale = coordinate_scale(rig);
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    SCOPED_TRACE(name + " " + to_string(normals) +
                 (dispatch == RigDispatch::kPerComponent ? " per component" : " by path shape"));
    const DeformedBatch<float> fused =
        test::run_on_device(deformer, batch, values, normals, RigPath::kFused);
    const DeformedBatch<float> passes =
        test::run_on_device(deformer, batch, values, normals, RigPath::kPasses);
    const DeformedBatch<double> exact = run_reference(model, values, normals);

    const Difference between = max_difference(fused, passes, mesh.vertex_count(), instances);
    EXPECT_LT(between.position, 1e-6 * scale);
    EXPECT_LT(between.normal, 1e-5);
    const Difference to_reference = max_difference(fused, exact, mesh.vertex_count(), instances);
    EXPECT_LT(to_reference.position, 4e-6 * scale * static_cast<double>(longest));
    EXPECT_LT(to_reference.normal, 2e-5 * static_cast<double>(longest));
  }
}

// Both ways of generating the dispatch code (each device gets one of them).
void expect_paths_agree_with_each_other_and_the_reference(const Mesh& mesh, const Rig& rig,
                                                          const std::string& name) {
  for (RigDispatch dispatch : {RigDispatch::kPerComponent, RigDispatch::kByPathShape})
    expect_paths_agree_with_each_other_and_the_reference(mesh, rig, name, dispatch);
}

TEST(RigDeformer, DeepTreeFusedPassesAndReferenceAgree) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ASSERT_EQ(rig.components.size(), 5u);
  EXPECT_EQ(rig.depth(4), 4u);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  EXPECT_EQ(deformer.pass_count(), 5u);  // one stage per level
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "deep tree");
}

TEST(RigDeformer, LongChainFusedPassesAndReferenceAgree) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  const Rig rig = resolve_rig(long_chain_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  EXPECT_EQ(deformer.pass_count(), 5u);  // one per chain position
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "long chain");
}

// A root and a grandchild without stages between stage-bearing components: the
// multi-pass path copies the stage-less ones and moves the others only as often as
// they have stages.
RigSpec rig_with_stageless_components() {
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  spec.components.push_back(root({}));
  const double big = 10.0;
  spec.components.push_back(box_component("tail", "body", glm::dvec3(-big),
                                          glm::dvec3(-0.1, big, big), {hinge("tail_angle", 0.3)}));
  spec.components.push_back(
      box_component("tip", "tail", glm::dvec3(0.5, -big, -big), glm::dvec3(big), {}));
  spec.components.push_back(box_component("head", "body", glm::dvec3(0.3, -big, -big),
                                          glm::dvec3(big), {bend("head_m"), hinge("nod", 0.1)}));
  return spec;
}

TEST(RigDeformer, StagelessComponentsAreCopiedOnThePassesPath) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  const Rig rig = resolve_rig(rig_with_stageless_components(), mesh);
  ASSERT_EQ(rig.components.size(), 4u);
  ASSERT_TRUE(rig.path(0).empty());
  for (const RigComponent& component : rig.components)
    ASSERT_FALSE(component.vertices.empty()) << component.name;
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  EXPECT_EQ(deformer.pass_count(), 2u);  // depth 1: chain positions 0 and 1
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "stageless components");
}

TEST(RigDeformer, PassesMoveEachVertexOnlyThroughItsOwnStages) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  // Five stages on every vertex: four intermediate results, each written and read once.
  ClDeformer long_chain(test::shared_context(),
                        RiggedMesh(mesh, resolve_rig(long_chain_rig(), mesh)), rig_kernels());
  EXPECT_DOUBLE_EQ(long_chain.scratch_records_per_slot(), 8.0);
  // One stage on every vertex: no intermediate results.
  RigSpec single;
  single.frame.mode = FrameSpec::Mode::kIdentity;
  single.components.push_back(root({bend("m")}));
  ClDeformer one_stage(test::shared_context(), RiggedMesh(mesh, resolve_rig(single, mesh)),
                       rig_kernels());
  EXPECT_DOUBLE_EQ(one_stage.scratch_records_per_slot(), 0.0);
}

TEST(RigDeformer, ShippedRigsFusedPassesAndReferenceAgree) {
  const std::pair<const char*, const char*> shipped[] = {
      {"blub/fish.obj", "rigs/blub.rig.json"},
      {"blub/fish_low_resolution.obj", "rigs/blub_low_resolution.rig.json"},
      {"barramundi/BarramundiFish.gltf", "rigs/barramundi.rig.json"}};
  for (const auto& [fish, rig_file] : shipped) {
    const Mesh mesh = load_mesh(test::data_path(fish));
    const Rig rig = resolve_rig(load_rig_file(test::data_path(rig_file)), mesh);
    EXPECT_GE(rig.components.size(), 3u) << rig_file;  // body, caudal fin, a paired fin
    expect_paths_agree_with_each_other_and_the_reference(mesh, rig, fish);
  }
}

TEST(RigDeformer, SingleBendRigMatchesTheBendKernel) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const BodyFrame frame = find_body_frame(mesh);
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    const RiggedMesh model = RiggedMesh::single_bend(mesh, frame, mode);
    const RigParameters m = test::bend_fractions(model, {0.7});
    ClDeformer rig_deformer(test::shared_context(), model, rig_kernels());
    ASSERT_FALSE(rig_deformer.uses_single_bend_kernel());
    ClDeformer bend_deformer(test::shared_context(), model);
    ASSERT_TRUE(bend_deformer.uses_single_bend_kernel());
    const Difference d = max_difference(
        test::run_on_device(rig_deformer, m, NormalMode::kJacobian),
        test::run_on_device(bend_deformer, m, NormalMode::kJacobian), mesh.vertex_count(), 1);
    EXPECT_LT(d.position, 2e-6 * coordinate_scale(model.rig()));
    EXPECT_LT(d.normal, 2e-5);
  }
}

TEST(RigDeformer, ComponentMovesOnlyItsOwnVerticesUntilItsParentDoes) {
  const Mesh mesh = test::synthetic_fish(96, 32);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  DeviceBatch batch = deformer.allocate(1);
  RigParameters values(rig, 1);
  values.set(0, "tail3_angle", 0.6f);  // level 3 only; every other stage at rest
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    const DeformedBatch<float> out =
        test::run_on_device(deformer, batch, values, NormalMode::kRotate, path);
    // Components in depth-first order: 0 body, 1 tail1, 2 tail2, 3 tail3, 4 tail4.
    std::vector<bool> in_tail3(mesh.vertex_count(), false);
    for (std::size_t c = 3; c < 5; ++c) {
      for (std::uint32_t v : rig.components[c].vertices) in_tail3[v] = true;
    }
    double outside = 0.0, inside = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const double moved =
          glm::length(glm::dvec3(out.position(0, v)) - glm::dvec3(mesh.positions[v]));
      (in_tail3[v] ? inside : outside) = std::max(in_tail3[v] ? inside : outside, moved);
    }
    EXPECT_LT(outside, 1e-6) << to_string(path);
    EXPECT_GT(inside, 1e-3) << to_string(path);
  }
}

TEST(RigDeformer, ChildFollowsItsParent) {
  // Deforming with (body_m, tail angle) equals bending, with the body's frame, the mesh
  // that the tail hinge alone produced: the child's result rides on the parent's bend.
  const Mesh mesh = test::synthetic_fish(96, 32);
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  spec.components.push_back(root({bend("body_m")}));
  spec.components.push_back(box_component(
      "tail", "body", glm::dvec3(-10.0), glm::dvec3(-0.2, 10.0, 10.0), {hinge("tail_angle", 0.2)}));
  const RiggedMesh model(mesh, resolve_rig(spec, mesh));
  RigParameters both(model, 1), tail_only(model, 1);
  both.set(0, "body_m", 0.6f);
  both.set(0, "tail_angle", 0.5f);
  tail_only.set(0, "tail_angle", 0.5f);
  const Mesh hinged = instance_mesh(mesh, run_reference(model, tail_only, NormalMode::kRotate), 0);
  const RiggedMesh body_only =
      RiggedMesh::single_bend(hinged, BodyFrame::identity(), BendMode::kExact);
  const DeformedBatch<double> composed =
      run_reference(body_only, test::values_of(body_only, {0.6f}), NormalMode::kRotate);
  const DeformedBatch<double> direct = run_reference(model, both, NormalMode::kRotate);
  const Difference d = max_difference(direct, composed, mesh.vertex_count(), 1);
  EXPECT_LT(d.position, 1e-6);  // float rounding of the intermediate mesh only
  EXPECT_LT(d.normal, 1e-6);
}

TEST(RigDeformer, SlotsKeepComponentsContiguousAndIndicesRemapped) {
  const Mesh mesh = test::synthetic_fish(96, 32);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  const std::vector<std::uint32_t>& slots = deformer.slot_of_vertex();
  const std::size_t slot_count = deformer.layout(1).plane_stride;
  EXPECT_EQ(slot_count % ClDeformer::kGroupSize, 0u);
  std::vector<bool> used(slot_count, false);
  for (std::uint32_t slot : slots) {
    ASSERT_LT(slot, slot_count);
    EXPECT_FALSE(used[slot]);
    used[slot] = true;
  }
  for (const RigComponent& component : rig.components) {
    std::uint32_t low = UINT32_MAX, high = 0;
    for (std::uint32_t v : component.vertices) {
      low = std::min(low, slots[v]);
      high = std::max(high, slots[v]);
    }
    EXPECT_EQ(high - low + 1, component.vertices.size()) << component.name;
    EXPECT_EQ(low % ClDeformer::kGroupSize, 0u) << component.name;
  }
  ASSERT_EQ(deformer.remapped_indices().size(), mesh.indices.size());
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
    EXPECT_EQ(deformer.remapped_indices()[k], slots[mesh.indices[k]]);
  }
}

TEST(RigDeformer, HeterogeneousFrameEqualsSeparateRuns) {
  // Two species in one frame: the synthetic fish with its deep rig and the Blub with
  // its shipped rig, different instance counts, one enqueue.
  const Mesh synthetic = test::synthetic_fish(64, 24);
  const Mesh blub = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const Rig synthetic_rig = resolve_rig(deep_tail_rig(), synthetic);
  const Rig blub_rig =
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), blub);
  ClDeformer a(test::shared_context(), RiggedMesh(synthetic, synthetic_rig));
  ClDeformer b(test::shared_context(), RiggedMesh(blub, blub_rig));
  RigFrame frame;
  const std::size_t first = frame.add(a, 7);
  const std::size_t second = frame.add(b, 3);
  frame.parameters(first) = random_parameters(synthetic_rig, 7, 0.7, 1);
  frame.parameters(second) = random_parameters(blub_rig, 3, 0.7, 2);
  const std::vector<cl::Event> done = frame.enqueue(NormalMode::kJacobian);
  ASSERT_EQ(done.size(), 2u);
  const DeformedBatch<float> together_a = a.read(frame.batch(first));
  const DeformedBatch<float> together_b = b.read(frame.batch(second));

  const DeformedBatch<float> alone =
      test::run_on_device(a, frame.parameters(first), NormalMode::kJacobian);
  EXPECT_EQ(max_difference(alone, together_a, synthetic.vertex_count(), 7).position, 0.0);
  const DeformedBatch<float> alone_b =
      test::run_on_device(b, frame.parameters(second), NormalMode::kJacobian);
  EXPECT_EQ(max_difference(alone_b, together_b, blub.vertex_count(), 3).position, 0.0);
}

// Kernel arguments are set only when a frame goes to another batch than the kernel's
// last one (and again when a batch gains scratch sets): alternating batches and paths
// must each get their own frames.
TEST(RigDeformer, AlternatingBatchesAndPathsEachGetTheirOwnFrames) {
  const Mesh mesh = test::synthetic_fish(64, 24);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  const RiggedMesh model(mesh, rig);
  ClDeformer deformer(test::shared_context(), model, rig_kernels());
  DeviceBatch first = deformer.allocate(3);
  DeviceBatch second = deformer.allocate(2);
  const RigParameters a = random_parameters(rig, 3, 0.7, 21);
  const RigParameters b = random_parameters(rig, 2, 0.7, 22);
  const RigParameters c = random_parameters(rig, 3, 0.7, 23);
  auto enqueue = [&](const RigParameters& values, DeviceBatch& batch, RigPath path) {
    ClJob job;
    job.model = &model;
    job.parameters = values.view();
    job.path = path;
    job.outputs = &batch;
    deformer.enqueue(job);
  };
  enqueue(a, first, RigPath::kFused);
  enqueue(b, second, RigPath::kPasses);
  enqueue(c, first, RigPath::kPasses);
  // Parameters for another instance count: rejected, the batch keeps its frame.
  EXPECT_THROW(enqueue(a, second, RigPath::kFused), Error);
  const DeformedBatch<float> from_first = deformer.read(first);
  const DeformedBatch<float> from_second = deformer.read(second);

  ClDeformer fresh(test::shared_context(), model, rig_kernels());
  const DeformedBatch<float> expected_first =
      test::run_on_device(fresh, c, NormalMode::kRotate, RigPath::kPasses);
  const DeformedBatch<float> expected_second =
      test::run_on_device(fresh, b, NormalMode::kRotate, RigPath::kPasses);
  EXPECT_EQ(max_difference(from_first, expected_first, mesh.vertex_count(), 3).position, 0.0);
  EXPECT_EQ(max_difference(from_second, expected_second, mesh.vertex_count(), 2).position, 0.0);
}

TEST(RigDeformer, SeveralInstancesPerWorkItemGiveTheSameResult) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const Rig rig = resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh);
  const RiggedMesh model(mesh, rig);
  const RigParameters values = random_parameters(rig, 7, 0.7, 5);  // an odd count
  ClDeformer one(test::shared_context(), model, rig_kernels(RigDispatch::kAuto, 1));
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    const DeformedBatch<float> expected =
        test::run_on_device(one, values, NormalMode::kJacobian, path);
    for (std::size_t per_item : {2u, 3u, 4u}) {
      ClDeformer several(test::shared_context(), model, rig_kernels(RigDispatch::kAuto, per_item));
      const DeformedBatch<float> got =
          test::run_on_device(several, values, NormalMode::kJacobian, path);
      const Difference d = max_difference(got, expected, mesh.vertex_count(), 7);
      EXPECT_LT(d.position, 1e-6 * coordinate_scale(rig)) << per_item << " " << to_string(path);
      EXPECT_LT(d.normal, 1e-5) << per_item << " " << to_string(path);
    }
  }
}

TEST(RigDeformer, BadParametersAreRejectedByName) {
  const Mesh mesh = test::synthetic_fish(48, 16);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  DeviceBatch batch = deformer.allocate(2);
  RigParameters values(rig, 2);
  EXPECT_THROW(values.set(0, "no_such_param", 1.0f), Error);
  EXPECT_THROW(values.set(2, "body_m", 1.0f), Error);
  values.set(1, "tail1_angle", 4.0f);  // beyond pi
  try {
    test::run_on_device(deformer, batch, values, NormalMode::kRotate);
    FAIL() << "expected an out-of-range error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutOfRange);
    EXPECT_EQ(e.field(), "tail1_angle[1]");
  }
  values.set(1, "tail1_angle", NAN);
  EXPECT_THROW(test::run_on_device(deformer, batch, values, NormalMode::kRotate), Error);
  RigParameters wrong_count(rig, 3);
  EXPECT_THROW(test::run_on_device(deformer, batch, wrong_count, NormalMode::kRotate), Error);
  EXPECT_THROW(parse_rig_path("sideways"), Error);
}

}  // namespace
}  // namespace finflex

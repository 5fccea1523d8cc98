// Rigged deformation: the fused and multi-pass OpenCL paths against each other and
// against the CPU reference that applies the chains literally (METHOD.md section 2),
// on every shipped rig and on deep and long synthetic rigs, with parameters up to
// their full limits; the limits themselves, computed independently; RigFrame on every
// path, normal mode and format.
//
// Tolerances, and why:
//  - fused vs passes: the same float32 operations in the same order, the passes only
//    storing intermediate float32 values: 1e-6 (|origin| + s_x) for positions, 1e-5 for
//    normals and tangents (the compilers may contract a multiply-add differently per
//    kernel; measured: 0 on PoCL, at the limits too);
//  - against the double reference: every stage adds a few float32 ulps, so the
//    single-bend bounds (finflex/accuracy.hpp) times the length of the longest path.
//    Random parameters stay below 0.8 of their limits; the instances at the full
//    limits are compared with compare_to_reference, whose bounds follow each vertex's
//    conditioning, and every Jacobian normal (the skipped ones included) with a bound
//    that adds the reference's own spread under float rounding of the rest mesh.
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
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

// Random parameters within `fraction` of each one's limit; a table (a spine's angles)
// a smooth wave of random amplitude and phase, 0.3 rad at most (angles drawn sample by
// sample would fold the spine).
RigParameters random_parameters(const Rig& rig, std::size_t instances, double fraction,
                                unsigned seed) {
  RigParameters values(rig, instances);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-fraction, fraction);
  for (std::size_t i = 0; i < instances; ++i) {
    for (const RigParameter& parameter : rig.parameters) {
      float* row = values.values().data() + i * values.values_per_instance() + parameter.offset;
      if (parameter.count == 1) {
        row[0] = static_cast<float>(uniform(random) * parameter.limit);
        continue;
      }
      const double amplitude = 0.3 * uniform(random), phase = 3.0 * uniform(random);
      for (std::size_t k = 0; k < parameter.count; ++k) {
        row[k] = static_cast<float>(amplitude *
                                    std::sin(6.0 * double(k) / double(parameter.count) + phase));
      }
    }
  }
  return values;
}

// The generic rig kernels (not the single-bend one), dispatched as `dispatch` says.
ClTuning rig_kernels(RigDispatch dispatch = RigDispatch::kAuto, std::size_t per_item = 0) {
  ClTuning options;
  options.dispatch = dispatch;
  options.instances_per_item = per_item;
  options.single_bend_kernel = false;
  return options;
}

using test::Difference;
using test::max_difference;

// Scale of the coordinates the kernels handle: the root frame's origin and length.
double coordinate_scale(const Rig& rig) {
  const BodyFrame& f = rig.components.front().frame;
  return glm::length(f.origin) + f.length;
}

// How far the reference's Jacobian normals move when the rest mesh moves by 4 float32
// roundings of the coordinate scale along each axis (the kernels hold the rest mesh
// in float): near a range limit or a fold this is the size of the problem's own
// uncertainty; elsewhere it is far below 1e-5.
DeformedBatch<double> rounding_spread(const RiggedMesh& model, const RigParameters& values,
                                      const DeformedBatch<double>& exact) {
  const double delta = 4.0 * std::ldexp(1.0, -24) * coordinate_scale(model.rig());
  DeformedBatch<double> spread = exact;  // normals: the largest move; the rest unused
  std::fill(spread.normals.begin(), spread.normals.end(), 0.0);
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      Mesh moved = model.mesh();
      for (glm::vec3& p : moved.positions) p[axis] += static_cast<float>(sign * delta);
      const DeformedBatch<double> there =
          run_reference(RiggedMesh(moved, model.rig()), values, NormalMode::kJacobian);
      for (std::size_t i = 0; i < values.instance_count(); ++i) {
        for (std::size_t v = 0; v < model.vertex_count(); ++v) {
          const double move = glm::length(there.normal(i, v) - exact.normal(i, v));
          const std::size_t at = spread.shape.index(i, 0, v);
          spread.normals[at] = std::max(spread.normals[at], move);
        }
      }
    }
  }
  return spread;
}

// Instances 0-4: random parameters within 0.8 of their limits; 5-8: every parameter
// at its full limit (both signs, alternate parameters opposite), at 0.95 and at 0.6.
const std::size_t kRandom = 5, kAtLimits = 4;

RigParameters random_and_limit_parameters(const RiggedMesh& model) {
  const RigParameters random = random_parameters(model.rig(), kRandom, 0.8, 11);
  const RigParameters limits = test::at_fractions_of_the_limits(model, {1.0, -1.0, 0.95, -0.6});
  RigParameters values(model, kRandom + kAtLimits);
  values.values() = random.values();
  values.values().insert(values.values().end(), limits.values().begin(), limits.values().end());
  return values;
}

// Both ways of generating the dispatch code (each device gets one of them), against
// each other's paths and the reference. `skipped_at_limits`: the Jacobian normals
// compare_to_reference counts as ill-defined (near a range limit or a fold); a
// property of the reference alone, so the same on every device (measured on this rig;
// a wider margin would show here).
void expect_paths_agree_with_each_other_and_the_reference(const Mesh& mesh, const Rig& rig,
                                                          const std::string& name,
                                                          std::size_t skipped_at_limits) {
  const RiggedMesh model(mesh, rig);
  for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
    EXPECT_NEAR(rig.parameters[p].limit, test::expected_limit(mesh, rig, p),
                1e-12 * test::expected_limit(mesh, rig, p))
        << name << " " << rig.parameters[p].name;
  }
  const RigDispatch dispatches[] = {RigDispatch::kPerComponent, RigDispatch::kByPathShape};
  std::vector<std::unique_ptr<ClDeformer>> deformers;
  for (RigDispatch dispatch : dispatches) {
    deformers.push_back(
        std::make_unique<ClDeformer>(test::shared_context(), model, rig_kernels(dispatch)));
  }
  const std::size_t instances = kRandom + kAtLimits;
  const RigParameters values = random_and_limit_parameters(model);
  const std::size_t longest = std::max<std::size_t>(model.longest_path(), 1);
  const double scale = coordinate_scale(rig);
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    const DeformedBatch<double> exact = run_reference(model, values, normals);
    const DeformedBatch<double> spread = normals == NormalMode::kJacobian
                                             ? rounding_spread(model, values, exact)
                                             : DeformedBatch<double>{};
    for (std::size_t d = 0; d < deformers.size(); ++d) {
      SCOPED_TRACE(
          name + " " + to_string(normals) +
          (dispatches[d] == RigDispatch::kPerComponent ? " per component" : " by path shape"));
      ClDeformer& deformer = *deformers[d];
      DeviceBatch batch = deformer.allocate(instances);
      const DeformedBatch<float> fused =
          test::run_on_device(deformer, batch, values, normals, RigPath::kFused);
      const DeformedBatch<float> passes =
          test::run_on_device(deformer, batch, values, normals, RigPath::kPasses);

      // Every instance, the limits included: the paths agree on every attribute.
      const Difference between = max_difference(fused, passes, mesh.vertex_count(), instances);
      EXPECT_LT(between.position, 1e-6 * scale);
      EXPECT_LT(between.normal, 1e-5);
      EXPECT_LT(between.tangent, 1e-5);
      EXPECT_EQ(between.tangents_compared, mesh.has_tangents());
      // The random instances, every vertex, at the bounds of the longest path.
      const Difference to_reference = max_difference(fused, exact, mesh.vertex_count(), kRandom);
      EXPECT_LT(to_reference.position, 4e-6 * scale * static_cast<double>(longest));
      EXPECT_LT(to_reference.normal, 2e-5 * static_cast<double>(longest));
      EXPECT_LT(to_reference.tangent, 2e-5 * static_cast<double>(longest));
      // Every instance with the bounds that follow each vertex's conditioning (the
      // passes are within 1e-6 of the fused path, above).
      const AccuracyReport report =
          compare_to_reference(model, values.view(), normals, fused, exact);
      EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
      EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
      EXPECT_EQ(report.skipped_normals,
                normals == NormalMode::kJacobian ? skipped_at_limits : std::size_t{0});
      if (normals != NormalMode::kJacobian) continue;
      // The normals compare_to_reference skips are compared too: every normal within
      // the bound of its path plus twice the reference's own spread there.
      double worst_ratio = 0.0;
      std::size_t worst_instance = 0, worst_vertex = 0;
      for (std::size_t i = 0; i < instances; ++i) {
        for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
          const double stages = static_cast<double>(
              std::max<std::size_t>(model.paths()[model.component_of_vertex()[v]].size(), 1));
          const double error = glm::length(glm::dvec3(fused.normal(i, v)) - exact.normal(i, v));
          const double ratio =
              error / (2e-5 * stages + 2.0 * spread.normals[spread.shape.index(i, 0, v)]);
          if (ratio > worst_ratio) {
            worst_ratio = ratio;
            worst_instance = i;
            worst_vertex = v;
          }
        }
      }
      EXPECT_LE(worst_ratio, 1.0) << "instance " << worst_instance << " vertex " << worst_vertex;
    }
  }
}

TEST(RigDeformer, DeepTreeFusedPassesAndReferenceAgree) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ASSERT_EQ(rig.components.size(), 5u);
  EXPECT_EQ(rig.depth(4), 4u);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  EXPECT_EQ(internal::pass_count(deformer), 5u);  // one stage per level
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "deep tree", 4);
}

TEST(RigDeformer, LongChainFusedPassesAndReferenceAgree) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  const Rig rig = resolve_rig(long_chain_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  EXPECT_EQ(internal::pass_count(deformer), 5u);  // one per chain position
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "long chain", 4);
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
  EXPECT_EQ(internal::pass_count(deformer), 2u);  // depth 1: chain positions 0 and 1
  expect_paths_agree_with_each_other_and_the_reference(mesh, rig, "stageless components", 6);
}

TEST(RigDeformer, PassesMoveEachVertexOnlyThroughItsOwnStages) {
  const Mesh mesh = test::synthetic_fish(96, 32, true);
  // Five stages on every vertex: four intermediate results, each written and read once.
  ClDeformer long_chain(test::shared_context(),
                        RiggedMesh(mesh, resolve_rig(long_chain_rig(), mesh)), rig_kernels());
  EXPECT_DOUBLE_EQ(internal::scratch_records_per_slot(long_chain), 8.0);
  // One stage on every vertex: no intermediate results.
  RigSpec single;
  single.frame.mode = FrameSpec::Mode::kIdentity;
  single.components.push_back(root({bend("m")}));
  ClDeformer one_stage(test::shared_context(), RiggedMesh(mesh, resolve_rig(single, mesh)),
                       rig_kernels());
  EXPECT_DOUBLE_EQ(internal::scratch_records_per_slot(one_stage), 0.0);
}

struct ShippedRig {
  const char* fish;
  const char* rig;
  std::size_t skipped_at_limits;
};

void expect_shipped_rigs_agree(const std::vector<ShippedRig>& shipped) {
  for (const ShippedRig& c : shipped) {
    const Mesh mesh = load_mesh(test::data_path(c.fish));
    const Rig rig = resolve_rig(load_rig_file(test::data_path(c.rig)), mesh);
    EXPECT_GE(rig.components.size(), 3u) << c.rig;  // body, caudal fin, a paired fin
    expect_paths_agree_with_each_other_and_the_reference(mesh, rig, c.fish, c.skipped_at_limits);
  }
}

TEST(RigDeformer, ShippedRigsFusedPassesAndReferenceAgree) {
  expect_shipped_rigs_agree(
      {{"blub/fish_low_resolution.obj", "rigs/blub_low_resolution.rig.json", 17},
       {"barramundi/BarramundiFish.gltf", "rigs/barramundi.rig.json", 0}});
}

// The full-resolution Blub's rig: a large test (tests/CMakeLists.txt).
TEST(RigDeformerLarge, FullResolutionShippedRigFusedPassesAndReferenceAgree) {
  expect_shipped_rigs_agree({{"blub/fish.obj", "rigs/blub.rig.json", 107}});
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
    EXPECT_LT(d.tangent, 2e-5);
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
  const Mesh mesh = test::synthetic_fish(96, 32, true);
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
  EXPECT_LT(d.tangent, 1e-6);
}

TEST(RigDeformer, SlotsKeepComponentsContiguousAndIndicesRemapped) {
  const Mesh mesh = test::synthetic_fish(96, 32);
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  ClDeformer deformer(test::shared_context(), RiggedMesh(mesh, rig), rig_kernels());
  const std::vector<std::uint32_t>& slots = deformer.slot_of_vertex();
  const std::size_t slot_count = deformer.layout(1).positions.plane_stride;
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

// The deep rig on the synthetic fish with tangents, as DeepTreeFusedPassesAndReferenceAgree
// deforms it (the frame tests below share its kernels).
const Mesh& deep_fish() {
  static const Mesh mesh = test::synthetic_fish(96, 32, true);
  return mesh;
}

// Two species in one frame: the synthetic fish (with tangents) with its deep rig and the
// Blub with its shipped rig, different instance counts, one enqueue; on both paths and
// both normal modes, and with half normals, each entry equal to a separate run of it,
// every attribute.
TEST(RigDeformer, HeterogeneousFrameEqualsSeparateRuns) {
  const Mesh& synthetic = deep_fish();
  const Mesh blub = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const Rig synthetic_rig = resolve_rig(deep_tail_rig(), synthetic);
  const Rig blub_rig =
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), blub);
  ClDeformer a(test::shared_context(), RiggedMesh(synthetic, synthetic_rig));
  ClDeformer b(test::shared_context(), RiggedMesh(blub, blub_rig));
  struct Setting {
    NormalFormat format;
    NormalMode normals;
    RigPath path;
  };
  const Setting settings[] = {{NormalFormat::kFloat32, NormalMode::kJacobian, RigPath::kFused},
                              {NormalFormat::kFloat32, NormalMode::kJacobian, RigPath::kPasses},
                              {NormalFormat::kFloat32, NormalMode::kRotate, RigPath::kFused},
                              {NormalFormat::kFloat32, NormalMode::kRotate, RigPath::kPasses},
                              {NormalFormat::kHalf, NormalMode::kJacobian, RigPath::kPasses}};
  for (const auto& [format, normals, path] : settings) {
    RigFrame frame;
    const std::size_t first = frame.add(a, 7, format);
    const std::size_t second = frame.add(b, 3, format);
    EXPECT_EQ(frame.size(), 2u);
    EXPECT_EQ(frame.batch(first).shape.normal_format, format);
    frame.parameters(first) = random_parameters(synthetic_rig, 7, 0.7, 1);
    frame.parameters(second) = random_parameters(blub_rig, 3, 0.7, 2);
    SCOPED_TRACE(std::string(to_string(format)) + " " + to_string(normals) + " " + to_string(path));
    const std::vector<cl::Event> done = frame.enqueue(normals, path);
    ASSERT_EQ(done.size(), 2u);
    const DeformedBatch<float> together_a = a.read(frame.batch(first));
    const DeformedBatch<float> together_b = b.read(frame.batch(second));

    const Difference d_a = max_difference(
        test::run_on_device(a, frame.parameters(first), normals, path, false, format), together_a,
        synthetic.vertex_count(), 7);
    EXPECT_EQ(d_a.position, 0.0);
    EXPECT_EQ(d_a.normal, 0.0);
    EXPECT_EQ(d_a.tangent, 0.0);
    EXPECT_TRUE(d_a.tangents_compared);
    const Difference d_b = max_difference(
        test::run_on_device(b, frame.parameters(second), normals, path, false, format), together_b,
        blub.vertex_count(), 3);
    EXPECT_EQ(d_b.position, 0.0);
    EXPECT_EQ(d_b.normal, 0.0);
  }
}

// "Every entry's job is validated and its parameters checked before any is launched":
// a bad second entry (a value out of its own range, though under the other
// parameters' limits; NaN; a parameter set for another instance count) leaves the
// first entry's outputs as the last good frame wrote them.
TEST(RigDeformer, RigFrameChecksEveryEntryBeforeLaunchingAny) {
  const Mesh& synthetic = deep_fish();
  const Mesh blub = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const Rig synthetic_rig = resolve_rig(deep_tail_rig(), synthetic);
  const Rig blub_rig =
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), blub);
  ClDeformer a(test::shared_context(), RiggedMesh(synthetic, synthetic_rig));
  ClDeformer b(test::shared_context(), RiggedMesh(blub, blub_rig));
  RigFrame frame;
  const std::size_t first = frame.add(a, 3);
  const std::size_t second = frame.add(b, 2);
  frame.parameters(first) = random_parameters(synthetic_rig, 3, 0.5, 31);
  frame.parameters(second) = random_parameters(blub_rig, 2, 0.5, 32);
  frame.enqueue(NormalMode::kRotate);
  const DeformedBatch<float> good_a = a.read(frame.batch(first));
  const DeformedBatch<float> good_b = b.read(frame.batch(second));

  const RigParameters next_a = random_parameters(synthetic_rig, 3, 0.5, 33);
  const RigParameters good_second = frame.parameters(second);
  const std::size_t body_m = blub_rig.param_index("body_m");
  const float body_limit = static_cast<float>(blub_rig.parameters[body_m].limit);
  ASSERT_LT(1.5f * body_limit, 3.1f);  // between the bend's limit and the hinges' pi
  RigParameters beyond_its_own(blub_rig, 2);
  beyond_its_own.values() = good_second.values();
  beyond_its_own.set(1, "body_m", 1.5f * body_limit);
  RigParameters nan(blub_rig, 2);
  nan.values() = good_second.values();
  nan.set(0, "tail_angle", NAN);
  const std::pair<RigParameters, std::string> bad_second[] = {
      {beyond_its_own, "body_m[1]"},
      {nan, "tail_angle[0]"},
      {RigParameters(blub_rig, 4), "job.outputs"}};
  for (const auto& [bad, field] : bad_second) {
    SCOPED_TRACE(field);
    frame.parameters(first) = next_a;
    frame.parameters(second) = bad;
    try {
      frame.enqueue(NormalMode::kRotate);
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      EXPECT_EQ(e.field(), field);
    }
    const Difference d_a =
        max_difference(a.read(frame.batch(first)), good_a, synthetic.vertex_count(), 3);
    EXPECT_EQ(d_a.position, 0.0);
    EXPECT_EQ(d_a.normal, 0.0);
    EXPECT_EQ(d_a.tangent, 0.0);
    const Difference d_b =
        max_difference(b.read(frame.batch(second)), good_b, blub.vertex_count(), 2);
    EXPECT_EQ(d_b.position, 0.0);
    EXPECT_EQ(d_b.normal, 0.0);
  }
  // With the second entry good again, the first gets its new values.
  frame.parameters(second) = good_second;
  frame.enqueue(NormalMode::kRotate);
  const Difference d = max_difference(a.read(frame.batch(first)),
                                      test::run_on_device(a, next_a, NormalMode::kRotate),
                                      synthetic.vertex_count(), 3);
  EXPECT_EQ(d.position, 0.0);
  EXPECT_GT(
      max_difference(a.read(frame.batch(first)), good_a, synthetic.vertex_count(), 3).position,
      1e-3);
}

// Kernel arguments are set only when a frame goes to another batch than the kernel's
// last one (and again when a batch gains scratch sets): alternating batches and paths
// must each get their own frames.
TEST(RigDeformer, AlternatingBatchesAndPathsEachGetTheirOwnFrames) {
  const Mesh& mesh = deep_fish();
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
    job.instances = values.instance_count();
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
  const Difference d_first = max_difference(from_first, expected_first, mesh.vertex_count(), 3);
  const Difference d_second = max_difference(from_second, expected_second, mesh.vertex_count(), 2);
  for (const Difference& d : {d_first, d_second}) {
    EXPECT_EQ(d.position, 0.0);
    EXPECT_EQ(d.normal, 0.0);
    EXPECT_EQ(d.tangent, 0.0);
    EXPECT_TRUE(d.tangents_compared);
  }
}

// The fused and multi-pass paths of `rig_file`'s rig on the Barramundi, with several
// instances per work-item (the shapes below) against one.
void expect_several_per_item_match_one(const std::string& rig_file) {
  SCOPED_TRACE(rig_file);
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const Rig rig = resolve_rig(load_rig_file(test::data_path(rig_file)), mesh);
  const RiggedMesh model(mesh, rig);
  const RigParameters values = random_parameters(rig, 7, 0.7, 5);  // an odd count
  ClDeformer one(test::shared_context(), model, rig_kernels(RigDispatch::kAuto, 1));
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    const DeformedBatch<float> expected =
        test::run_on_device(one, values, NormalMode::kJacobian, path);
    // The device's own dispatch with 2, 3 and 4 per item, and the GPUs' shapes (stages
    // compiled in per component, 4 per item; 8 for a rig with a spine) forced on
    // whatever device runs this.
    const std::pair<RigDispatch, std::size_t> shapes[] = {{RigDispatch::kAuto, 2},
                                                          {RigDispatch::kAuto, 3},
                                                          {RigDispatch::kAuto, 4},
                                                          {RigDispatch::kPerComponent, 4},
                                                          {RigDispatch::kPerComponent, 8}};
    for (const auto& [dispatch, per_item] : shapes) {
      ClDeformer several(test::shared_context(), model, rig_kernels(dispatch, per_item));
      EXPECT_EQ(internal::instances_per_item(several, several.layout(1, NormalFormat::kFloat32)),
                per_item);
      const DeformedBatch<float> got =
          test::run_on_device(several, values, NormalMode::kJacobian, path);
      const Difference d = max_difference(got, expected, mesh.vertex_count(), 7);
      SCOPED_TRACE(testing::Message()
                   << per_item << " per item, "
                   << (dispatch == RigDispatch::kPerComponent ? "per component" : "auto dispatch")
                   << ", " << to_string(path));
      EXPECT_LT(d.position, 1e-6 * coordinate_scale(rig));
      EXPECT_LT(d.normal, 1e-5);
      EXPECT_LT(d.tangent, 1e-5);
      EXPECT_TRUE(d.tangents_compared);
    }
  }
}

TEST(RigDeformer, SeveralInstancesPerWorkItemGiveTheSameResult) {
  expect_several_per_item_match_one("rigs/barramundi.rig.json");
}

// The same with a spine (its derived values per instance): a large test (its kernels
// take a CPU's OpenCL compiler minutes; tests/CMakeLists.txt).
TEST(RigDeformerLarge, SeveralInstancesPerWorkItemWithASpineGiveTheSameResult) {
  expect_several_per_item_match_one("rigs/barramundi_swim.rig.json");
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

// Each value is checked against its own parameter's limit: values between two limits
// (above a bend's 0.5 / x_max, below the hinges' pi) are refused for the bend and
// accepted for a hinge, by both backends and by check_parameters, and clamping brings
// each one to its own limit.
TEST(RigDeformer, EachParameterIsCheckedAgainstItsOwnLimit) {
  const Mesh& mesh = deep_fish();
  const Rig rig = resolve_rig(deep_tail_rig(), mesh);
  const RiggedMesh model(mesh, rig);
  ClDeformer deformer(test::shared_context(), model, rig_kernels());
  DeviceBatch batch = deformer.allocate(2);
  const double pi = 3.14159265358979323846;
  // The limits themselves: the body's bend on x in [-0.5, 0.5] (identity frame), 1;
  // the paper bends of tail2 and tail4 in their own frames; the hinges' pi.
  for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
    EXPECT_NEAR(rig.parameters[p].limit, test::expected_limit(mesh, rig, p), 1e-12)
        << rig.parameters[p].name;
  }
  EXPECT_DOUBLE_EQ(rig.parameters[rig.param_index("body_m")].limit, 1.0);
  EXPECT_DOUBLE_EQ(rig.parameters[rig.param_index("tail1_angle")].limit, pi);
  EXPECT_DOUBLE_EQ(rig.parameters[rig.param_index("tail3_angle")].limit, pi);
  // tail2's frame starts at its cut and spans its extent: x_max 1, limit 0.5, below
  // the body's 1, so 0.525 is refused for tail2_m while the body would take it.
  EXPECT_NEAR(rig.parameters[rig.param_index("tail2_m")].limit, 0.5, 1e-3);

  for (const char* name : {"body_m", "tail2_m", "tail4_m"}) {
    const double limit = rig.parameters[rig.param_index(name)].limit;
    ASSERT_LT(1.05 * limit, 3.0) << name;  // under pi: refused only by its own limit
    RigParameters values(rig, 2);
    values.set(0, name, static_cast<float>(limit));  // at the limit: accepted
    values.set(1, name, static_cast<float>(-1.05 * limit));
    const std::string field = std::string(name) + "[1]";
    try {
      test::run_on_device(deformer, batch, values, NormalMode::kRotate);
      ADD_FAILURE() << name << ": expected an out-of-range error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kOutOfRange) << name;
      EXPECT_EQ(e.field(), field);
    }
    try {
      run_reference(model, values, NormalMode::kRotate);
      ADD_FAILURE() << name << ": expected an out-of-range error from the reference";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kOutOfRange) << name;
      EXPECT_EQ(e.field(), field);
    }
    std::vector<float> clamped(values.values().size());
    check_parameters(rig, values.view(), /*clamp=*/true, clamped.data());
    const std::size_t at =
        values.values_per_instance() + rig.parameters[rig.param_index(name)].offset;
    EXPECT_LE(std::fabs(double(clamped[at])), limit) << name;
    EXPECT_NEAR(clamped[at], -limit, 1e-6 * limit) << name;
    values.set(1, name, static_cast<float>(0.99 * limit));
    EXPECT_NO_THROW(test::run_on_device(deformer, batch, values, NormalMode::kRotate)) << name;
  }
  // A hinge takes values up to pi, above every bend's limit here.
  RigParameters hinge_values(rig, 2);
  hinge_values.set(0, "tail1_angle", 3.1f);
  hinge_values.set(1, "tail3_angle", -3.1f);
  EXPECT_NO_THROW(test::run_on_device(deformer, batch, hinge_values, NormalMode::kRotate));
  EXPECT_NO_THROW(run_reference(model, hinge_values, NormalMode::kRotate));
  // Clamped, each to its own limit: the body's m to 1, the angle to pi.
  RigParameters beyond(rig, 1);
  beyond.set(0, "body_m", 2.0f);
  beyond.set(0, "tail1_angle", -4.0f);
  std::vector<float> clamped(beyond.values().size());
  check_parameters(rig, beyond.view(), /*clamp=*/true, clamped.data());
  EXPECT_NEAR(clamped[rig.parameters[rig.param_index("body_m")].offset], 1.0, 1e-6);
  EXPECT_NEAR(clamped[rig.parameters[rig.param_index("tail1_angle")].offset], -pi, 1e-6);
  // The device clamps the same way: its output equals the output at those values.
  DeviceBatch one = deformer.allocate(1);
  const DeformedBatch<float> on_device =
      test::run_on_device(deformer, one, beyond, NormalMode::kRotate, RigPath::kAuto, true);
  const DeformedBatch<float> at_limits =
      test::run_on_device(deformer, one, test::values_of(model, clamped), NormalMode::kRotate);
  const Difference d = max_difference(on_device, at_limits, mesh.vertex_count(), 1);
  EXPECT_EQ(d.position, 0.0);
  EXPECT_EQ(d.normal, 0.0);
  EXPECT_EQ(d.tangent, 0.0);
}

}  // namespace
}  // namespace finflex

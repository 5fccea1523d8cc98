// The spine deformer (METHOD.md section 6): a table of tangent angles along x. Checked
// against its definition (identity at zero angles, the spine's arc length kept at
// angles the paper's series cannot reach, the paper's bend as the special case
// theta = asin(2 m x)), the OpenCL kernels against the double reference on a
// synthetic and a real fish, and fold-over refused or clamped.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A whole-body spine of `samples` angles (parameter "wave") in the identity frame.
RiggedMesh spine_model(const Mesh& mesh, std::size_t samples,
                       FrameSpec::Mode frame = FrameSpec::Mode::kIdentity) {
  RigSpec spec;
  spec.frame.mode = frame;
  ComponentSpec body;
  body.name = "body";
  StageSpec stage = make_stage("spine", "wave");
  set_option(stage, "samples", double(samples));
  body.chain.push_back(stage);
  spec.components.push_back(body);
  return RiggedMesh(mesh, resolve_rig(spec, mesh));
}

// The sample positions of the spine stage's table.
std::vector<double> sample_x(const RiggedMesh& model) {
  const RigStage& stage = model.rig().components[0].chain[0];
  const std::size_t n = model.rig().parameters[0].count;
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = stage.geometry.x_lowest +
           (stage.geometry.x_highest - stage.geometry.x_lowest) * double(k) / double(n - 1);
  }
  return x;
}

// One instance per function: its angles at the samples.
RigParameters angles(const RiggedMesh& model,
                     const std::vector<std::function<double(double)>>& functions) {
  const std::vector<double> x = sample_x(model);
  RigParameters values(model, functions.size());
  for (std::size_t i = 0; i < functions.size(); ++i) {
    std::vector<float> row;
    for (double xk : x) row.push_back(static_cast<float>(functions[i](xk)));
    values.set(i, "wave", row);
  }
  return values;
}

double spine_length(const DeformedBatch<float>& batch, std::size_t instance, std::size_t count) {
  double length = 0.0;
  for (std::size_t v = 1; v < count; ++v) {
    length += glm::length(glm::dvec3(batch.position(instance, v)) -
                          glm::dvec3(batch.position(instance, v - 1)));
  }
  return length;
}

// A sample count that is not a whole number in [2, 256] (NaN included, as a hand-made
// RigSpec may hold) is named before the deformer reads it (found by fuzzing).
TEST(Spine, BadSampleCountsAreNamedBeforeUse) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  for (const double samples : {std::nan(""), 1.0, 2.5, 257.0, -1.0, 1e300}) {
    RigSpec spec;
    spec.frame.mode = FrameSpec::Mode::kIdentity;
    ComponentSpec body;
    body.name = "body";
    StageSpec stage = make_stage("spine", "wave");
    stage.options[0] = samples;  // "samples", written past set_option's own check
    body.chain.push_back(stage);
    spec.components.push_back(body);
    try {
      resolve_rig(spec, mesh);
      ADD_FAILURE() << "samples = " << samples << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.field(), "components[0] 'body'.chain[0].samples") << e.what();
    }
  }
}

TEST(Spine, ZeroAnglesAreTheIdentity) {
  const Mesh mesh = test::synthetic_fish(32, 16, true);
  const RiggedMesh model = spine_model(mesh, 32);
  const RigParameters zero(model, 1);
  const DeformedBatch<double> out = run_reference(model, zero, NormalMode::kJacobian);
  ClDeformer deformer(test::shared_context(), model);
  const DeformedBatch<float> device = test::run_on_device(deformer, zero, NormalMode::kJacobian);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_LT(glm::length(out.position(0, v) - glm::dvec3(mesh.positions[v])), 1e-12);
    EXPECT_LT(glm::length(glm::dvec3(device.position(0, v)) - glm::dvec3(mesh.positions[v])), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(device.normal(0, v)) - glm::dvec3(mesh.normals[v])), 1e-6);
  }
}

TEST(Spine, KeepsTheSpineArcLengthWhereThePaperSeriesCannotGo) {
  // A ribbon on the spine, x in [-0.5, 0.5]: angles up to 2.5 rad (143 degrees), a
  // travelling wave and a C-shape beyond the paper's range |2 m x| <= 1.
  const int points = 4001;
  const Mesh ribbon = test::spine_ribbon(points, 0.5);
  const RiggedMesh model = spine_model(ribbon, 64);
  const RigParameters values =
      angles(model, {[](double x) { return 2.5 * std::sin(2.0 * kPi * x); },
                     [](double x) { return 2.4 * x + 0.3; },
                     [](double x) { return -1.2 * std::cos(7.0 * x); }});
  ClDeformer deformer(test::shared_context(), model);
  const DeformedBatch<float> device = test::run_on_device(deformer, values, NormalMode::kRotate);
  const DeformedBatch<double> exact = run_reference(model, values, NormalMode::kRotate);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT(std::fabs(spine_length(device, i, points) - 1.0), 1e-5) << "instance " << i;
    double reference_length = 0.0;
    for (std::size_t v = 1; v < std::size_t(points); ++v)
      reference_length += glm::length(exact.position(i, v) - exact.position(i, v - 1));
    // The polyline through 4001 points is shorter than the curve by about
    // k^2 h^2 / 24 (k <= 16, h = 1 / 4000): 7e-7 at most.
    EXPECT_LT(std::fabs(reference_length - 1.0), 1e-6) << "instance " << i;
  }
  // The pivot (x = 0, the ribbon's middle) stays fixed.
  EXPECT_LT(glm::length(device.position(0, points / 2)), 1e-6);
}

TEST(Spine, ThePaperBendIsTheCaseThetaEqualsAsinTwoMX) {
  // The exact bend with m, against a spine of angles asin(2 m x_k): piecewise linear
  // angles differ from asin by O(h^2), so the shapes agree to about 1e-4 of the length
  // with 64 samples at 0.8 of the bend's range.
  const Mesh mesh = test::synthetic_fish(48, 24);
  const RiggedMesh spine = spine_model(mesh, 64);
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, BodyFrame::identity(), BendMode::kExact);
  const double m = 0.8 * test::bend_limit(bend);
  const RigParameters table =
      angles(spine, {[m](double x) { return std::asin(std::clamp(2.0 * m * x, -1.0, 1.0)); }});
  const DeformedBatch<double> from_spine = run_reference(spine, table, NormalMode::kJacobian);
  const DeformedBatch<double> from_bend =
      run_reference(bend, test::values_of(bend, {float(m)}), NormalMode::kJacobian);
  double position = 0.0, normal = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    position =
        std::max(position, glm::length(from_spine.position(0, v) - from_bend.position(0, v)));
    normal = std::max(normal, glm::length(from_spine.normal(0, v) - from_bend.normal(0, v)));
  }
  EXPECT_LT(position, 2e-4);
  EXPECT_LT(normal, 2e-2);  // the Jacobian's curvature is piecewise constant in the table
  EXPECT_GT(position, 0.0);
}

// Every dispatch, normal mode and path against the reference on `mesh`.
void expect_device_matches_the_reference(const Mesh& mesh, FrameSpec::Mode frame) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> amplitude(-0.8, 0.8), phase(0.0, 2.0 * kPi);
  std::vector<std::function<double(double)>> waves;
  for (int i = 0; i < 5; ++i) {
    const double a = amplitude(random), b = amplitude(random), p = phase(random);
    waves.push_back([a, b, p](double x) { return a * std::sin(6.0 * x + p) + b * x; });
  }
  {
    const RiggedMesh model = spine_model(mesh, 32, frame);
    const RigParameters values = angles(model, waves);
    for (const ClTuning& options :
         {ClTuning{0, RigDispatch::kPerComponent, true},
          ClTuning{0, RigDispatch::kByPathShape, true}, ClTuning{3, RigDispatch::kAuto, true}}) {
      ClDeformer deformer(test::shared_context(), model, options);
      for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
        for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
          SCOPED_TRACE(std::string(to_string(normals)) + " " + to_string(path));
          const DeformedBatch<float> device = test::run_on_device(deformer, values, normals, path);
          const AccuracyReport report = compare_to_reference(model, values.view(), normals, device,
                                                             run_reference(model, values, normals));
          EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
          EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
          EXPECT_EQ(report.skipped_normals, 0u);
        }
      }
    }
  }
}

TEST(Spine, DeviceMatchesTheReference) {
  expect_device_matches_the_reference(test::synthetic_fish(64, 32, true),
                                      FrameSpec::Mode::kIdentity);
}

// The same on the Barramundi (its spine's segment tables from a scanned mesh): a large
// test (tests/CMakeLists.txt).
TEST(SpineLarge, DeviceMatchesTheReferenceOnTheBarramundi) {
  expect_device_matches_the_reference(load_mesh(test::data_path("barramundi/BarramundiFish.gltf")),
                                      FrameSpec::Mode::kAuto);
}

void expect_every_table_size_matches(std::size_t table_items,
                                     const std::vector<std::size_t>& sample_counts);

// rig_prepare shares a table's samples out over several work-items per instance on
// GPUs, one work-item per instance on CPUs (kernels/deformers/spine.cl): 1, 8 and 64,
// on every device, with tables smaller than the work-items, one sample per work-item,
// more than one (up to the 256 allowed), and x = 0 inside the table or beyond its end.
// Only powers of two up to 64 are taken. The default run takes tables of 3 and 65
// samples (fewer than 8 work-items, more than 64) with 1 and 64 work-items; SpineLarge
// the others (8 work-items; 2, 63, 64, 129, 200 and 256 samples: one sample per
// work-item, up to the 256 allowed), each a program of its own to build (a large test:
// tests/CMakeLists.txt).
TEST(Spine, DeviceMatchesTheReferenceForEveryTableSize) {
  for (std::size_t items : {1u, 64u}) {
    SCOPED_TRACE("table items " + std::to_string(items));
    expect_every_table_size_matches(items, {3, 65});
  }
  ClTuning odd;
  odd.table_items = 3;
  ClTuning too_many;
  too_many.table_items = 128;
  EXPECT_THROW(
      ClDeformer(test::shared_context(), spine_model(test::synthetic_fish(16, 8), 32), too_many),
      Error);
  try {
    ClDeformer(test::shared_context(), spine_model(test::synthetic_fish(16, 8), 32), odd);
    FAIL() << "expected an error naming tuning.table_items";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "tuning.table_items");
  }
}

// The fused path with `table_items` work-items per instance against the reference.
AccuracyReport fused_against_reference(const RiggedMesh& model, const RigParameters& values,
                                       std::size_t table_items) {
  ClTuning options;
  options.table_items = table_items;
  ClDeformer deformer(test::shared_context(), model, options);
  const DeformedBatch<float> device =
      test::run_on_device(deformer, values, NormalMode::kRotate, RigPath::kFused);
  return compare_to_reference(model, values.view(), NormalMode::kRotate, device,
                              run_reference(model, values, NormalMode::kRotate));
}

TEST(SpineLarge, DeviceMatchesTheReferenceForEveryTableSizeAndSampleCount) {
  expect_every_table_size_matches(8, {3, 65});
  for (std::size_t items : {1u, 8u, 64u}) {
    SCOPED_TRACE("table items " + std::to_string(items));
    expect_every_table_size_matches(items, {2, 63, 64, 129, 200, 256});
  }
}

void expect_every_table_size_matches(std::size_t table_items,
                                     const std::vector<std::size_t>& sample_counts) {
  const Mesh mesh = test::synthetic_fish(64, 32, true);
  Mesh shifted = mesh;  // in the identity frame, x = 0 lies before the table's start
  for (glm::vec3& p : shifted.positions) p.x += 2.0f;
  const auto wave = [](double x) { return 0.4 * std::sin(5.0 * x + 0.3) + 0.2 * x; };
  for (std::size_t samples : sample_counts) {
    for (const FrameSpec::Mode frame : {FrameSpec::Mode::kIdentity, FrameSpec::Mode::kAuto}) {
      SCOPED_TRACE("samples " + std::to_string(samples));
      const RiggedMesh model = spine_model(mesh, samples, frame);
      const AccuracyReport report = fused_against_reference(
          model, angles(model, {wave, [](double x) { return -0.3 * x; }}), table_items);
      EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
      EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
    }
    SCOPED_TRACE("x = 0 beyond the table, samples " + std::to_string(samples));
    const RiggedMesh model = spine_model(shifted, samples, FrameSpec::Mode::kIdentity);
    const AccuracyReport report = fused_against_reference(
        model, angles(model, {[](double x) { return 0.3 * (x - 2.0); }}), table_items);
    EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
  }
}

// CPU lane kernels read a spine record once when a work-item's 16 lanes share its
// segment, blend the records of up to 4 neighbouring segments, and gather beyond
// (kernels/deformers/spine.cl): thin tubes of 3 vertices a ring put 16 lanes over
// about 5 rings, so 256 samples over 512 rings spread them over 2-3 segments and over
// 98 rings over about 14, and 32 samples over 512 rings keep most in one; each against
// the reference, with a wave and with a bend turning within a few segments. The
// body's lanes come from the rest planes, sorted by x, and take their segments from
// the first and last lane: 98 rings (290 vertices) leave the last work-item 2 vertices
// in 2 segments and 14 lanes of padding, which must repeat the last vertex to keep
// them sorted.
TEST(Spine, LanesSharingBlendingOrGatheringRecordsMatchTheReference) {
  for (const auto& [rings, samples] :
       {std::pair{512, 256}, std::pair{98, 256}, std::pair{512, 32}}) {
    SCOPED_TRACE(std::to_string(rings) + " rings, " + std::to_string(samples) + " samples");
    const RiggedMesh model = spine_model(test::synthetic_fish(rings, 3), std::size_t(samples));
    const RigParameters values =
        angles(model, {[](double x) { return 0.5 * std::sin(9.0 * x); },
                       [](double x) { return 0.8 * std::tanh(20.0 * (x - 0.1)); }});
    ClDeformer deformer(test::shared_context(), model);
    const DeformedBatch<float> device =
        test::run_on_device(deformer, values, NormalMode::kRotate, RigPath::kFused);
    const AccuracyReport report =
        compare_to_reference(model, values.view(), NormalMode::kRotate, device,
                             run_reference(model, values, NormalMode::kRotate));
    EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
    EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
  }
}

// A spine's component (and a fin under it) has its slots in the order of x along the
// spine's frame, so the lanes of a work-item (and a GPU's warp) mostly share a segment;
// a rig without a table keeps the mesh's order.
TEST(Spine, SlotsOfASpineComponentFollowX) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh model = spine_model(mesh, 32, FrameSpec::Mode::kAuto);
  ClDeformer deformer(test::shared_context(), model);
  const BodyFrame& frame = model.rig().components.front().chain.front().frame;
  std::vector<std::pair<std::uint32_t, double>> by_slot;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    by_slot.emplace_back(deformer.slot_of_vertex()[v],
                         frame.point_to_local(glm::dvec3(mesh.positions[v])).x);
  }
  std::sort(by_slot.begin(), by_slot.end());
  for (std::size_t i = 1; i < by_slot.size(); ++i) {
    ASSERT_LE(by_slot[i - 1].second, by_slot[i].second) << "slot " << by_slot[i].first;
  }
  // A fin under the spine (its own chain a hinge) is sorted along the spine too.
  const Mesh blub = load_mesh(test::data_path("blub/fish.obj"));
  const RiggedMesh swim(
      blub, resolve_rig(load_rig_file(test::data_path("rigs/blub_swim.rig.json")), blub));
  ClDeformer swim_deformer(test::shared_context(), swim);
  const BodyFrame& spine = swim.rig().components.front().chain.front().frame;
  ASSERT_GT(swim.rig().components.size(), 1u);
  for (const RigComponent& component : swim.rig().components) {
    SCOPED_TRACE(component.name);
    std::vector<std::pair<std::uint32_t, double>> slots_and_x;
    for (std::uint32_t v : component.vertices) {
      slots_and_x.emplace_back(swim_deformer.slot_of_vertex()[v],
                               spine.point_to_local(glm::dvec3(blub.positions[v])).x);
    }
    std::sort(slots_and_x.begin(), slots_and_x.end());
    for (std::size_t i = 1; i < slots_and_x.size(); ++i)
      ASSERT_LE(slots_and_x[i - 1].second, slots_and_x[i].second);
  }
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  ClDeformer in_mesh_order(test::shared_context(), bend);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    ASSERT_EQ(in_mesh_order.slot_of_vertex()[v], v);
  }
}

TEST(Spine, FoldOverIsRefusedOrClampedNeverDrawn) {
  // A sharp kink: one segment turning by 1.5 rad folds the thick body through itself.
  const Mesh mesh = test::synthetic_fish(64, 32);
  const RiggedMesh model = spine_model(mesh, 32);
  const RigParameters kink = angles(model, {[](double x) { return x > 0.1 ? 1.5 : 0.0; }});
  try {
    run_reference(model, kink, NormalMode::kRotate);
    FAIL() << "expected a fold-over error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutOfRange);
    EXPECT_EQ(e.field(), "wave[0]");
    EXPECT_NE(std::string(e.what()).find("folds the surface"), std::string::npos) << e.what();
  }
  ClDeformer deformer(test::shared_context(), model);
  EXPECT_THROW(test::run_on_device(deformer, kink, NormalMode::kRotate), Error);
  // Clamped: bent less, so that nothing folds.
  std::vector<float> clamped(kink.values().size());
  check_parameters(model.rig(), kink.view(), true, clamped.data());
  const RigParameters fixed = test::values_of(model, clamped);
  EXPECT_EQ(count_folded_vertices(model, fixed.view(), 0), 0u);
  EXPECT_GT(count_folded_vertices(model, kink.view(), 0), 0u);
  const DeformedBatch<float> device =
      test::run_on_device(deformer, kink, NormalMode::kRotate, RigPath::kAuto, true);
  const DeformedBatch<double> reference = run_reference(model, fixed, NormalMode::kRotate);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    EXPECT_LT(glm::length(glm::dvec3(device.position(0, v)) - reference.position(0, v)), 1e-5);
}

TEST(Spine, RigFilesNameItWithItsSamples) {
  const RigSpec spec = parse_rig_json(R"({"frame": {"mode": "identity"}, "components": [
      {"name": "body", "select": "all",
       "chain": [{"deformer": "spine", "samples": 40, "param": "wave"}]}]})");
  const Rig rig = resolve_rig(spec, test::synthetic_fish(16, 8));
  ASSERT_EQ(rig.parameters.size(), 1u);
  EXPECT_EQ(rig.parameters[0].count, 40u);
  EXPECT_DOUBLE_EQ(rig.parameters[0].limit, kPi);
  EXPECT_THROW(parse_rig_json(R"({"components": [{"name": "body", "select": "all",
       "chain": [{"deformer": "spine", "samples": 1.5, "param": "wave"}]}]})"),
               Error);
  RigParameters values(rig, 2);
  EXPECT_THROW(values.set(0, "wave", 0.5f), Error);  // a table takes 40 values
  values.set(1, "wave", std::vector<float>(40, 0.25f));
  EXPECT_EQ(values.values()[40 + 39], 0.25f);
}

}  // namespace
}  // namespace finflex

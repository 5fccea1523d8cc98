// Kernels of several lanes (kernels/common/lanes.cl: a work-item deforms 8, 16 or 32
// consecutive slots with vector loads, arithmetic and stores; CPUs' default) against
// the one-lane kernels and the double reference: the whole-body bend on every bundled
// fish, every shipped rig (the swim rigs' spines included) on both paths, world
// placements, several instances per work-item, and the fall-back to one lane for half
// normals. Every lane count is forced through ClTuning::lanes, so this runs on any
// device; the other test programs run the device's own choice.
//
// Tolerances: against the reference, compare_to_reference's bounds
// (finflex/accuracy.hpp), as for the one-lane kernels. Lanes against one lane: the same
// float32 operations, which a compiler may contract differently into multiply-adds
// (vector and scalar code are selected apart): 1e-6 (|origin| + s_x) for positions, 1e-5
// for normals and tangents, as between the fused and multi-pass paths
// (test_rig_deformer.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

bool device_is_pocl() {
  const std::string& platform = test::shared_context().description().platform_name;
  return platform.find("Portable Computing Language") != std::string::npos;
}

// The lane counts the running test takes (LANES_TEST); empty: every one.
std::vector<std::size_t> lanes_of_this_run;

// Whether the running test is LanesLarge's.
bool this_run_is_large = false;
bool large_run() { return this_run_is_large; }

// Those of `lanes` that the shared context's device builds (32 on PoCL only) and this
// run takes; `large_only`: all of them in the large run, none in the default one.
std::vector<std::size_t> vector_lanes(std::vector<std::size_t> lanes = {8, 16, 32},
                                      bool large_only = false) {
  if (!device_is_pocl()) lanes.erase(std::remove(lanes.begin(), lanes.end(), 32), lanes.end());
  if (large_only) return large_run() ? lanes : std::vector<std::size_t>{};
  if (!lanes_of_this_run.empty()) {
    lanes.erase(std::remove_if(lanes.begin(), lanes.end(),
                               [](std::size_t l) {
                                 return std::find(lanes_of_this_run.begin(),
                                                  lanes_of_this_run.end(),
                                                  l) == lanes_of_this_run.end();
                               }),
                lanes.end());
  }
  return lanes;
}

// A test over the lane counts, registered twice: Lanes.NAME takes 16 lanes (and one),
// LanesLarge.NAME 8 and 32 (a large test: registered with FINFLEX_LARGE_TESTS,
// tests/CMakeLists.txt), and what a test leaves to it besides (large_run(): the
// full-resolution Blub's rigs, the plain stores of vertex structs). Together they check
// every case; each builds its own kernels, which is what takes a CPU's OpenCL compiler
// the time.
#define LANES_TEST(name)         \
  void name##_over_lanes();      \
  TEST(Lanes, name) {            \
    lanes_of_this_run = {16};    \
    this_run_is_large = false;   \
    name##_over_lanes();         \
  }                              \
  TEST(LanesLarge, name) {       \
    lanes_of_this_run = {8, 32}; \
    this_run_is_large = true;    \
    name##_over_lanes();         \
  }                              \
  void name##_over_lanes()

ClTuning with_lanes(std::size_t lanes, std::size_t per_item = 0) {
  ClTuning options;
  options.lanes = lanes;
  options.instances_per_item = per_item;
  return options;
}

// Scale of the coordinates the kernels handle: the root frame's origin and length.
double coordinate_scale(const Rig& rig) {
  const BodyFrame& f = rig.components.front().frame;
  return glm::length(f.origin) + f.length;
}

// The Barramundi with its swim rig (a spine, fins, padding slots, tangents).
RiggedMesh barramundi_swim() {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  return RiggedMesh(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi_swim.rig.json")), mesh));
}

// The exact whole-body bend on the low-resolution Blub (no tangents).
RiggedMesh blub_exact_bend() {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  return RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
}

// Instances swimming through their ranges: each single parameter at a fraction of its
// limit (up to 0.95, both signs), each table (a spine's angles) a travelling wave of
// up to 0.6 rad; then clamped as the backends clamp.
RigParameters swimming_values(const RiggedMesh& model, std::size_t instances) {
  RigParameters values(model, instances);
  const std::vector<RigParameter>& parameters = model.rig().parameters;
  for (std::size_t i = 0; i < instances; ++i) {
    const double phase = 1.3 * double(i);
    for (std::size_t p = 0; p < parameters.size(); ++p) {
      for (std::size_t k = 0; k < parameters[p].count; ++k) {
        const double along = double(k) / double(parameters[p].count);
        const double value = parameters[p].count == 1
                                 ? 0.95 * parameters[p].limit * std::sin(phase + double(p))
                                 : 0.6 * std::sin(6.0 * along + phase) * along;
        values.values()[i * values.values_per_instance() + parameters[p].offset + k] =
            static_cast<float>(value);
      }
    }
  }
  std::vector<float> clamped(values.values().size());
  check_parameters(model.rig(), values.view(), /*clamp=*/true, clamped.data());
  values.values() = clamped;
  return values;
}

void expect_within_reference_bounds(const RiggedMesh& model, const RigParameters& values,
                                    NormalMode normals, const DeformedBatch<float>& device,
                                    const DeformedBatch<double>& reference,
                                    const Placement* placements = nullptr) {
  const AccuracyReport report =
      compare_to_reference(model, values.view(), normals, device, reference, placements);
  EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
  EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
}

void expect_close_to_one_lane(const DeformedBatch<float>& lanes,
                              const DeformedBatch<float>& one_lane, std::size_t vertices,
                              std::size_t instances, double scale) {
  const test::Difference d = test::max_difference(lanes, one_lane, vertices, instances);
  EXPECT_LT(d.position, 1e-6 * scale);
  EXPECT_LT(d.normal, 1e-5);
  EXPECT_LT(d.tangent, 1e-5);
}

// The fused kernels of every lane count (vector_lanes) against one lane and the double
// reference, with both normal modes; `label` names the case in failures.
void expect_fused_lanes_match(const RiggedMesh& model, const RigParameters& values,
                              const std::string& label) {
  ClDeformer one_lane(test::shared_context(), model, with_lanes(1));
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    const DeformedBatch<double> reference = run_reference(model, values, normals);
    const DeformedBatch<float> scalar =
        test::run_on_device(one_lane, values, normals, RigPath::kFused);
    for (std::size_t lanes : vector_lanes()) {
      SCOPED_TRACE(label + " " + to_string(normals) + " " + std::to_string(lanes) + " lanes");
      ClDeformer vector(test::shared_context(), model, with_lanes(lanes));
      const DeformedBatch<float> device =
          test::run_on_device(vector, values, normals, RigPath::kFused);
      expect_within_reference_bounds(model, values, normals, device, reference);
      expect_close_to_one_lane(device, scalar, model.mesh().vertex_count(), values.instance_count(),
                               coordinate_scale(model.rig()));
    }
  }
}

TEST(Lanes, CpusTakeVectorsGpusOneLaneWhateverTheNormalFormat) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  const DeviceDescription& device = test::shared_context().description();
  ClDeformer automatic(test::shared_context(), model);
  // Two native vectors on PoCL (at least 8 lanes), one elsewhere (8 or 16).
  const std::size_t native = device.native_float_vector_width;
  std::size_t expected = native >= 16 ? 16 : 8;
  if (device_is_pocl()) expected = native >= 16 ? 32 : native >= 8 ? 16 : 8;
  if (device.is_gpu()) expected = 1;
  EXPECT_EQ(internal::lanes(automatic, automatic.layout(1, NormalFormat::kFloat32)), expected);
  EXPECT_EQ(internal::lanes(automatic, automatic.layout(1, NormalFormat::kHalf)), expected);
  for (std::size_t lanes : vector_lanes({1, 8, 16, 32})) {
    ClDeformer forced(test::shared_context(), model, with_lanes(lanes));
    EXPECT_EQ(internal::lanes(forced, forced.layout(1, NormalFormat::kFloat32)), lanes);
    EXPECT_EQ(internal::lanes(forced, forced.layout(1, NormalFormat::kHalf)), lanes);
  }
}

// And 32 lanes off PoCL (a vector type of clang's), with the device's platform named.
TEST(Lanes, OtherLaneCountsAreRefusedByName) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  std::vector<std::size_t> refused = {2, 4, 64};
  if (!device_is_pocl()) refused.push_back(32);
  for (std::size_t lanes : refused) {
    try {
      ClDeformer deformer(test::shared_context(), model, with_lanes(lanes));
      ADD_FAILURE() << lanes << " lanes were accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
      EXPECT_EQ(e.field(), "tuning.lanes");
      if (lanes == 32) {
        EXPECT_NE(std::string(e.what()).find(test::shared_context().description().platform_name),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

LANES_TEST(BendOnEveryBundledFishMatchesOneLaneAndTheReference) {
  for (const char* fish : test::kBundledFish) {
    const Mesh mesh = load_mesh(test::data_path(fish));
    const BodyFrame frame = find_body_frame(mesh);
    for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
      const RiggedMesh model = RiggedMesh::single_bend(mesh, frame, mode);
      const RigParameters m = test::bend_fractions(model, {0.0, 0.3, -0.7, 0.95, -1.0, 1.0});
      ClDeformer one_lane(test::shared_context(), model, with_lanes(1));
      for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
        const DeformedBatch<double> reference = run_reference(model, m, normals);
        const DeformedBatch<float> scalar = test::run_on_device(one_lane, m, normals);
        for (std::size_t lanes : vector_lanes()) {
          SCOPED_TRACE(std::string(fish) + " " + to_string(mode) + " " + to_string(normals) + " " +
                       std::to_string(lanes) + " lanes");
          ClDeformer vector(test::shared_context(), model, with_lanes(lanes));
          ASSERT_TRUE(vector.uses_single_bend_kernel());
          const DeformedBatch<float> device = test::run_on_device(vector, m, normals);
          expect_within_reference_bounds(model, m, normals, device, reference);
          expect_close_to_one_lane(device, scalar, mesh.vertex_count(), m.instance_count(),
                                   glm::length(frame.origin) + frame.length);
          EXPECT_EQ(device.shape.tangents, mesh.has_tangents());
        }
      }
    }
  }
}

// Every shipped rig: bends, hinges and the swim rigs' spines (a vertex's own segment
// gathered lane by lane), both dispatches of the rig kernels, both paths.
LANES_TEST(ShippedRigsWithSpinesMatchOneLaneAndTheReference) {
  struct Shipped {
    const char* fish;
    const char* rig;
    std::vector<std::size_t> lanes;  // besides 1: 16 everywhere, 8 and 32 on some
    bool large = false;              // every lane count in the large run only
  };
  const Shipped shipped[] = {
      {"blub/fish.obj", "rigs/blub.rig.json", {16}, true},
      {"blub/fish.obj", "rigs/blub_swim.rig.json", {16, 32}, true},
      {"blub/fish_low_resolution.obj", "rigs/blub_low_resolution.rig.json", {8, 16, 32}},
      {"blub/fish_low_resolution.obj", "rigs/blub_low_resolution_swim.rig.json", {8, 16, 32}},
      {"barramundi/BarramundiFish.gltf", "rigs/barramundi.rig.json", {16}},
      {"barramundi/BarramundiFish.gltf", "rigs/barramundi_swim.rig.json", {8, 16, 32}}};
  for (const Shipped& c : shipped) {
    if (c.large && !large_run()) continue;  // the full-resolution Blub's kernels
    const Mesh mesh = load_mesh(test::data_path(c.fish));
    const RiggedMesh model(mesh, resolve_rig(load_rig_file(test::data_path(c.rig)), mesh));
    const RigParameters values = swimming_values(model, 4);
    const double scale = coordinate_scale(model.rig());
    ClTuning scalar_options = with_lanes(1);
    ClDeformer one_lane(test::shared_context(), model, scalar_options);
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      const DeformedBatch<double> reference = run_reference(model, values, normals);
      const DeformedBatch<float> scalar =
          test::run_on_device(one_lane, values, normals, RigPath::kFused);
      for (std::size_t lanes : vector_lanes(c.lanes, c.large)) {
        for (RigDispatch dispatch : {RigDispatch::kByPathShape, RigDispatch::kPerComponent}) {
          ClTuning options = with_lanes(lanes);
          options.dispatch = dispatch;
          ClDeformer vector(test::shared_context(), model, options);
          for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
            SCOPED_TRACE(std::string(c.rig) + " " + to_string(normals) + " " + to_string(path) +
                         " " + std::to_string(lanes) + " lanes" +
                         (dispatch == RigDispatch::kPerComponent ? " per component" : ""));
            const DeformedBatch<float> device = test::run_on_device(vector, values, normals, path);
            expect_within_reference_bounds(model, values, normals, device, reference);
            expect_close_to_one_lane(device, scalar, mesh.vertex_count(), values.instance_count(),
                                     scale);
          }
        }
      }
    }
  }
}

// A spine whose first segments, at the thin tail, turn sharply (by 0.6 rad, half a turn
// above FF_GENTLE_HALF_TURN: the long polynomials of kernels/common/trig.cl; sharper
// would fold the surface, which the rig refuses) and whose others turn gently (the short
// ones), so that work-items of every lane count take both and some blend a sharp and a
// gentle segment.
LANES_TEST(SharplyAndGentlyTurningSpineSegmentsMatchOneLaneAndTheReference) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model(
      mesh,
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution_swim.rig.json")), mesh));
  RigParameters values = swimming_values(model, 3);
  std::size_t tables = 0;
  for (const RigParameter& parameter : model.rig().parameters) {
    if (parameter.count == 1) continue;
    ++tables;
    for (std::size_t i = 0; i < values.instance_count(); ++i) {
      float* table = values.values().data() + i * values.values_per_instance() + parameter.offset;
      for (std::size_t k = 0; k < 6; ++k)
        table[k] = (k % 2 == 0 ? 0.3f : -0.3f) * (i % 2 == 0 ? 1.0f : -1.0f);
    }
  }
  ASSERT_GT(tables, 0u);
  expect_fused_lanes_match(model, values, "");
}

// Fins whose hinges sweep them along the body's spine (kernels/deformers/spine.cl
// spine_stage_swept: the segments a work-item's lanes reach, per bin of the hinge's
// angle, from a table the rig program computes): every shipped swim rig, its fins'
// angles stepped through the table's range [-0.8, 0.8] rad by a little less than a bin
// (so that they land in every bin, next to its edges too) and beyond it, its spine a
// travelling wave.
LANES_TEST(FinsSweptAlongTheSpineMatchOneLaneAndTheReference) {
  struct Shipped {
    const char* fish;
    const char* rig;
  };
  const Shipped shipped[] = {
      {"blub/fish.obj", "rigs/blub_swim.rig.json"},
      {"blub/fish_low_resolution.obj", "rigs/blub_low_resolution_swim.rig.json"},
      {"barramundi/BarramundiFish.gltf", "rigs/barramundi_swim.rig.json"}};
  for (const Shipped& c : shipped) {
    const Mesh mesh = load_mesh(test::data_path(c.fish));
    const RiggedMesh model(mesh, resolve_rig(load_rig_file(test::data_path(c.rig)), mesh));
    constexpr std::size_t kInstances = 90;
    RigParameters values = swimming_values(model, kInstances);
    std::size_t fins = 0;
    for (const RigParameter& parameter : model.rig().parameters) {
      if (parameter.count != 1) continue;
      ++fins;
      for (std::size_t i = 0; i < kInstances; ++i) {
        // From -0.99 to 0.99 rad in steps of 0.0222 (a bin: 0.025).
        values.values()[i * values.values_per_instance() + parameter.offset] =
            static_cast<float>(-0.99 + 1.98 * double(i) / double(kInstances - 1));
      }
    }
    ASSERT_GE(fins, 2u) << c.rig;
    expect_fused_lanes_match(model, values, c.rig);
  }
}

// World placement as the last stage (kernels/common/placement.cl), from the job's host
// records: the whole-body bend and the swim rig of the Barramundi (tangents too).
LANES_TEST(PlacedInstancesMatchOneLaneAndTheReference) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  const RiggedMesh swim = barramundi_swim();
  std::vector<Placement> where(3);
  for (std::size_t i = 0; i < where.size(); ++i) {
    const float turn = 2.0f * float(i) - 2.5f;
    where[i].position = glm::vec3(1.5f * float(i) - 1.0f, 0.4f * float(i), -0.7f + 0.2f * float(i));
    where[i].orientation = glm::angleAxis(turn, glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f * turn)));
    where[i].length = 0.3f + 0.08f * float(i);
  }
  for (const RiggedMesh* model : {&bend, &swim}) {
    const RigParameters values = swimming_values(*model, where.size());
    ClDeformer one_lane(test::shared_context(), *model, with_lanes(1));
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      const DeformedBatch<double> reference =
          run_reference(*model, values, normals, false, where.data());
      auto placed_run = [&](ClDeformer& deformer) {
        return test::run_on_device(deformer, values, normals, RigPath::kAuto, false,
                                   NormalFormat::kFloat32, where.data());
      };
      const DeformedBatch<float> scalar = placed_run(one_lane);
      for (std::size_t lanes : vector_lanes()) {
        SCOPED_TRACE(std::string(model == &bend ? "bend " : "swim rig ") + to_string(normals) +
                     " " + std::to_string(lanes) + " lanes");
        ClDeformer vector(test::shared_context(), *model, with_lanes(lanes));
        const DeformedBatch<float> device = placed_run(vector);
        expect_within_reference_bounds(*model, values, normals, device, reference, where.data());
        // World coordinates: the scale is the fish's placement (lengths below 0.5 m,
        // positions within 3 m of the origin).
        expect_close_to_one_lane(device, scalar, mesh.vertex_count(), where.size(), 4.0);
      }
    }
  }
}

// Several instances per work-item with lanes: each reads its rest vertices once for all
// of them; 5 instances over 3 per item leave the last work-item one short.
TEST(Lanes, SeveralInstancesPerWorkItemGiveTheSameResult) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  const RiggedMesh rig(
      mesh,
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution_swim.rig.json")), mesh));
  for (const RiggedMesh* model : {&bend, &rig}) {
    const RigParameters values = swimming_values(*model, 5);
    ClDeformer one(test::shared_context(), *model, with_lanes(16, 1));
    ClDeformer three(test::shared_context(), *model, with_lanes(16, 3));
    EXPECT_EQ(internal::instances_per_item(three, three.layout(1, NormalFormat::kFloat32)), 3u);
    for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
      SCOPED_TRACE(std::string(model == &bend ? "bend " : "swim rig ") + to_string(path));
      const DeformedBatch<float> a = test::run_on_device(one, values, NormalMode::kJacobian, path);
      const DeformedBatch<float> b =
          test::run_on_device(three, values, NormalMode::kJacobian, path);
      expect_close_to_one_lane(b, a, mesh.vertex_count(), 5, coordinate_scale(model->rig()));
    }
  }
}

// The kind of store changes where the bytes go, not their values: streaming and plain
// stores, and outputs in a caller's memory that is not aligned to the vectors (PoCL
// runs kernels on a CL_MEM_USE_HOST_PTR buffer's own memory: stored with vstoren), all
// write the same bits.
TEST(Lanes, StreamingPlainAndUnalignedStoresWriteTheSameBits) {
  const RiggedMesh model = barramundi_swim();
  const RigParameters values = swimming_values(model, 3);
  ClTuning plain_options = with_lanes(16);
  plain_options.stores = OutputStores::kPlain;
  ClTuning streaming_options = with_lanes(16);
  streaming_options.stores = OutputStores::kStreaming;
  ClDeformer streaming(test::shared_context(), model, streaming_options);
  ClDeformer plain(test::shared_context(), model, plain_options);
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    SCOPED_TRACE(to_string(path));
    const DeformedBatch<float> a =
        test::run_on_device(streaming, values, NormalMode::kJacobian, path);
    const DeformedBatch<float> b = test::run_on_device(plain, values, NormalMode::kJacobian, path);
    test::expect_same_outputs(a, b);

    // The same outputs in host memory one float past a vector boundary.
    DeviceBatch unaligned = streaming.allocate(values.instance_count());
    const std::size_t floats = unaligned.shape.attribute_elements();
    std::vector<std::vector<float>> memory(3, std::vector<float>(floats + 16));
    cl::Buffer* buffers[] = {&unaligned.positions, &unaligned.normals, &unaligned.tangents};
    for (std::size_t k = 0; k < 3; ++k) {
      float* first = memory[k].data() + 1;
      ASSERT_NE(reinterpret_cast<std::uintptr_t>(first) % 64, 0u);
      *buffers[k] = cl::Buffer(test::shared_context().context(), CL_MEM_USE_HOST_PTR,
                               floats * sizeof(float), first);
    }
    const DeformedBatch<float> c =
        test::run_on_device(streaming, unaligned, values, NormalMode::kJacobian, path);
    test::expect_same_outputs(a, c);
  }
}

// Lanes apply per batch: FinFlex's planes in slot order (normals float32 or half,
// previous positions in float32 planes) are stored as vectors; any other output layout
// of a rig, lane by lane through the one-slot stores (kernels/common/outputs.cl), with
// the same arithmetic: close to a one-lane deformer's outputs in that layout and within
// the reference's bounds, never streamed (GPUs: one lane). The single bend in mesh order
// or with previous positions in another layout takes one lane.
TEST(Lanes, OtherOutputLayoutsStoreLaneByLaneAndMatchTheReference) {
  const RiggedMesh model = barramundi_swim();
  const RigParameters values = swimming_values(model, 3);
  const std::size_t instances = values.instance_count();
  ClDeformer sixteen(test::shared_context(), model, with_lanes(16));
  ClDeformer one_lane(test::shared_context(), model, with_lanes(1));
  const OutputLayout planes = sixteen.layout(instances);
  EXPECT_EQ(internal::lanes(sixteen, planes), 16u);
  EXPECT_EQ(internal::lanes(sixteen, sixteen.layout(instances, NormalFormat::kHalf)), 16u);
  // Other layouts lane by lane on CPUs; on GPUs one lane whatever the options ask.
  const std::size_t by_lane = test::shared_context().description().is_gpu() ? 1u : 16u;

  struct Case {
    const char* name;
    OutputLayout layout;
  };
  std::vector<Case> cases;
  const std::size_t slots = sixteen.output_vertices(VertexOrder::kSlots);
  OutputLayout packed = planes;
  packed.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots);
  packed.normals = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots);
  if (packed.tangents)
    packed.tangents = AttributeLayout::packed(AttributeFormat::kFloat32x4, slots);
  cases.push_back({"packed float32", packed});
  OutputLayout mesh_order = planes;
  mesh_order.order = VertexOrder::kMesh;
  const std::size_t vertices = sixteen.output_vertices(VertexOrder::kMesh);
  mesh_order.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, vertices);
  mesh_order.normals = mesh_order.positions;
  if (mesh_order.tangents) mesh_order.tangents = mesh_order.positions;
  cases.push_back({"mesh order", mesh_order});
  OutputLayout previous = planes;
  previous.previous_positions = AttributeLayout::packed(AttributeFormat::kFloat32x4, slots);
  cases.push_back({"packed previous positions", previous});
  OutputLayout offset = planes;
  offset.positions.offset = 64;
  cases.push_back({"positions at an offset", offset});

  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    const DeformedBatch<double> reference = run_reference(model, values, normals);
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(c.name) + " " + to_string(normals));
      EXPECT_EQ(internal::lanes(sixteen, c.layout), by_lane);
      DeviceBatch vector_batch = sixteen.allocate(instances, c.layout);
      DeviceBatch scalar_batch = one_lane.allocate(instances, c.layout);
      EXPECT_FALSE(internal::streams_outputs(sixteen, vector_batch));
      const DeformedBatch<float> got = test::run_on_device(sixteen, vector_batch, values, normals);
      const DeformedBatch<float> want =
          test::run_on_device(one_lane, scalar_batch, values, normals);
      expect_within_reference_bounds(model, values, normals, got, reference);
      expect_close_to_one_lane(got, want, model.vertex_count(), instances,
                               coordinate_scale(model.rig()));
    }
  }
  // The single bend in mesh order or with previous positions in another layout: one lane.
  const RiggedMesh bend = blub_exact_bend();
  ClDeformer bend_sixteen(test::shared_context(), bend, with_lanes(16));
  OutputLayout bend_mesh_order = bend_sixteen.layout(instances);
  bend_mesh_order.order = VertexOrder::kMesh;
  OutputLayout bend_previous = bend_sixteen.layout(instances);
  bend_previous.previous_positions = AttributeLayout::packed(
      AttributeFormat::kFloat32x3, bend_sixteen.output_vertices(VertexOrder::kSlots));
  EXPECT_EQ(internal::lanes(bend_sixteen, bend_mesh_order), 1u);
  EXPECT_EQ(internal::lanes(bend_sixteen, bend_previous), 1u);
  OutputLayout bend_packed = bend_sixteen.layout(instances);
  bend_packed.positions = AttributeLayout::packed(
      AttributeFormat::kFloat32x3, bend_sixteen.output_vertices(VertexOrder::kSlots));
  EXPECT_EQ(internal::lanes(bend_sixteen, bend_packed), by_lane);
}

// Previous positions in float32 planes laid out as the positions take the vector stores too: each
// lane count, streamed and plain, the bend on Blub and the Barramundi's swim rig (tangents), two
// frames on one batch. The first frame's previous positions are its own positions (no motion), the
// second's exactly the first's positions, read back as vectors before they were overwritten; the
// positions, normals and tangents are the same bits as the same lanes write without
// previous positions; and a caller's buffers one float off a vector boundary (vloadn,
// vstoren) hold the same bits again.
LANES_TEST(PreviousPositionPlanesAreVectorsHoldingTheFrameBefore) {
  const RiggedMesh bend = blub_exact_bend();
  const RiggedMesh swim = barramundi_swim();
  for (const RiggedMesh* model : {&bend, &swim}) {
    const RigParameters first = swimming_values(*model, 3);
    RigParameters second = swimming_values(*model, 3);
    std::reverse(second.values().begin(), second.values().end());
    std::vector<float> clamped(second.values().size());
    check_parameters(model->rig(), second.view(), /*clamp=*/true, clamped.data());
    second.values() = clamped;
    const std::size_t instances = first.instance_count();
    for (std::size_t lanes : vector_lanes()) {
      for (OutputStores stores : {OutputStores::kStreaming, OutputStores::kPlain}) {
        SCOPED_TRACE(std::string(model == &bend ? "bend" : "swim rig") + ", " +
                     std::to_string(lanes) + " lanes" +
                     (stores == OutputStores::kPlain ? ", plain" : ", streaming"));
        ClTuning options = with_lanes(lanes);
        options.stores = stores;
        ClDeformer deformer(test::shared_context(), *model, options);
        OutputLayout layout = deformer.layout(instances);
        layout.previous_positions = layout.positions;
        EXPECT_EQ(internal::lanes(deformer, layout), lanes);
        DeviceBatch batch = deformer.allocate(instances, layout);
        EXPECT_EQ(internal::streams_outputs(deformer, batch), stores == OutputStores::kStreaming);
        const DeformedBatch<float> one =
            test::run_on_device(deformer, batch, first, NormalMode::kJacobian);
        EXPECT_EQ(one.previous_positions, one.positions);
        const DeformedBatch<float> two =
            test::run_on_device(deformer, batch, second, NormalMode::kJacobian);
        EXPECT_EQ(two.previous_positions, one.positions);
        EXPECT_NE(two.positions, one.positions);
        const DeformedBatch<float> without =
            test::run_on_device(deformer, second, NormalMode::kJacobian);
        test::expect_same_outputs(two, without);

        // The same two frames in a caller's memory one float past a vector boundary.
        const std::size_t floats = batch.shape.attribute_elements();
        std::vector<std::vector<float>> memory(4, std::vector<float>(floats + 16));
        cl::Buffer buffers[4];
        for (std::size_t k = 0; k < 4; ++k) {
          float* start = memory[k].data() + 1;
          ASSERT_NE(reinterpret_cast<std::uintptr_t>(start) % 64, 0u);
          buffers[k] = cl::Buffer(test::shared_context().context(), CL_MEM_USE_HOST_PTR,
                                  floats * sizeof(float), start);
        }
        DeviceBatch unaligned = deformer.bind(
            instances, layout,
            {buffers[0], buffers[1], layout.tangents ? buffers[2] : cl::Buffer(), buffers[3]});
        const DeformedBatch<float> unaligned_one =
            test::run_on_device(deformer, unaligned, first, NormalMode::kJacobian);
        const DeformedBatch<float> unaligned_two =
            test::run_on_device(deformer, unaligned, second, NormalMode::kJacobian);
        test::expect_same_outputs(unaligned_two, two);
        EXPECT_EQ(unaligned_two.previous_positions, one.positions);
        EXPECT_EQ(unaligned_one.previous_positions, one.positions);
      }
    }
  }
}

// A vertex struct that its attributes fill, in one buffer (on CPUs unless staged), and
// attributes each in a tightly packed array of its own: every lane count transposes
// each work-item's structs (an array's: one attribute's) into whole vectors
// (kernels/cpu/lane_outputs.cl), for the bend on Blub (no tangents) and the
// Barramundi's swim rig (tangents), in every format they take (float32x3 and x4,
// float16x4, snorm16x4, octahedral16x2; structs of 16 to 48 bytes a vertex), members in
// different orders, streamed and plain, and from a run 3 words off a vector boundary
// (vstoren): both hold exactly what the same lanes write into arrays of the same
// formats padded by a word a vertex (stored lane by lane), and the words around each
// run stay as they were.
LANES_TEST(VertexStructsAndAttributeArraysAreTransposedIntoVectors) {
  if (test::shared_context().description().is_gpu()) GTEST_SKIP() << "CPUs' kernels";
  const RiggedMesh bend = blub_exact_bend();
  const RiggedMesh swim = barramundi_swim();
  using F = AttributeFormat;
  struct Member {
    F format;
    std::size_t at;  // bytes into the struct
  };
  struct Case {
    const RiggedMesh* model;
    const char* name;
    Member position, normal, tangent;
    bool large = false;  // in the large run only
  };
  const std::vector<Case> cases = {
      {&bend, "float32x3 position, normal", {F::kFloat32x3, 0}, {F::kFloat32x3, 12}, {}},
      {&bend, "float32x3 normal, position", {F::kFloat32x3, 12}, {F::kFloat32x3, 0}, {}},
      {&bend, "float32x3, octahedral", {F::kFloat32x3, 0}, {F::kOctahedral16x2, 12}, {}},
      {&bend, "snorm16x4, float32x4", {F::kFloat32x4, 8}, {F::kSnorm16x4, 0}, {}},
      {&bend, "float32x3, float16x4", {F::kFloat32x3, 0}, {F::kFloat16x4, 12}, {}},
      {&swim,
       "float32x3 position, normal, tangent",
       {F::kFloat32x3, 0},
       {F::kFloat32x3, 12},
       {F::kFloat32x3, 24}},
      {&swim,
       "float32x3 tangent, position, normal",
       {F::kFloat32x3, 12},
       {F::kFloat32x3, 24},
       {F::kFloat32x3, 0},
       true},
      {&swim,
       "float32x3, float16x4, snorm16x4",
       {F::kFloat32x3, 0},
       {F::kFloat16x4, 12},
       {F::kSnorm16x4, 20},
       true},
      {&swim,
       "octahedral tangent, float32x3, octahedral",
       {F::kFloat32x3, 4},
       {F::kOctahedral16x2, 16},
       {F::kOctahedral16x2, 0}},
      {&swim, "float32x4 x 3", {F::kFloat32x4, 0}, {F::kFloat32x4, 16}, {F::kFloat32x4, 32}, true},
  };
  // A buffer of `words` words filled with -7, with 64 more after them.
  auto guarded = [](std::size_t words) {
    std::vector<float> filled(words + 64, -7.0f);
    cl_int status = CL_SUCCESS;
    cl::Buffer buffer(test::shared_context().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      filled.size() * sizeof(float), filled.data(), &status);
    check_cl(status, "clCreateBuffer");
    return buffer;
  };
  // Its first `lead` words and those past `words` still -7.
  auto expect_guards = [](const cl::Buffer& buffer, std::size_t lead, std::size_t words) {
    std::vector<float> after(words + 64);
    check_cl(test::shared_context().queue().enqueueReadBuffer(
                 buffer, CL_TRUE, 0, after.size() * sizeof(float), after.data()),
             "clEnqueueReadBuffer");
    for (std::size_t k = 0; k < lead; ++k) ASSERT_EQ(after[k], -7.0f) << k;
    for (std::size_t k = words; k < after.size(); ++k) ASSERT_EQ(after[k], -7.0f) << k;
  };
  for (const Case& c : cases) {
    const bool tangents = c.model->mesh().has_tangents();
    const RigParameters values = swimming_values(*c.model, 3);
    const std::size_t instances = values.instance_count();
    const std::size_t stride = format_bytes(c.position.format) + format_bytes(c.normal.format) +
                               (tangents ? format_bytes(c.tangent.format) : 0);
    // Every case: streamed with every lane count; plain and off a vector boundary with
    // 16. The default run takes 16 lanes streamed of the cases not marked large; the
    // large run, the rest.
    const std::vector<std::size_t> lane_counts =
        large_run() ? vector_lanes({8, 16, 32}, /*large_only=*/true)
                    : (c.large ? std::vector<std::size_t>{} : vector_lanes());
    for (std::size_t lanes : lane_counts) {
      struct Run {
        OutputStores stores;
        std::size_t lead;  // words before the first struct
      };
      std::vector<Run> runs;
      if (large_run() != (!c.large && lanes == 16)) runs.push_back({OutputStores::kStreaming, 0});
      if (lanes == 16 && large_run())
        runs.insert(runs.end(), {{OutputStores::kPlain, 0}, {OutputStores::kStreaming, 3}});
      for (const Run& run : runs) {
        SCOPED_TRACE(testing::Message()
                     << c.name << ", " << lanes << " lanes, "
                     << (run.stores == OutputStores::kStreaming ? "streaming" : "plain")
                     << ", lead " << run.lead);
        const bool streams = run.stores == OutputStores::kStreaming;
        ClTuning options = with_lanes(lanes);
        options.stores = run.stores;
        ClDeformer d(test::shared_context(), *c.model, options);
        const std::size_t slots = d.output_vertices(VertexOrder::kSlots);
        const std::size_t lead_bytes = 4 * run.lead;
        // The struct, in one buffer.
        OutputLayout l;
        auto member = [&](const Member& m) {
          return AttributeLayout::packed(m.format, slots, stride, lead_bytes + m.at);
        };
        l.positions = member(c.position);
        l.normals = member(c.normal);
        if (tangents) l.tangents = member(c.tangent);
        EXPECT_EQ(internal::lanes(d, l), lanes);
        const std::size_t words = (lead_bytes + instances * slots * stride) / 4;
        const cl::Buffer one = guarded(words);
        DeviceBatch structs = d.bind(instances, l, {one, one, one, {}});
        EXPECT_EQ(internal::streams_outputs(d, structs), streams);
        // Each attribute in its own tight array, and (the oracle) padded by a word.
        auto arrays_of = [&](std::size_t padding, std::size_t lead) {
          OutputLayout a = l;
          auto array = [&](const Member& m) {
            return AttributeLayout::packed(m.format, slots, format_bytes(m.format) + padding, lead);
          };
          a.positions = array(c.position);
          a.normals = array(c.normal);
          if (tangents) a.tangents = array(c.tangent);
          return a;
        };
        const OutputLayout tight = arrays_of(0, lead_bytes);
        const Member* members[] = {&c.position, &c.normal, &c.tangent};
        std::vector<cl::Buffer> own;
        std::vector<std::size_t> own_words;
        for (std::size_t k = 0; k < (tangents ? 3u : 2u); ++k) {
          own_words.push_back((lead_bytes + instances * slots * format_bytes(members[k]->format)) /
                              4);
          own.push_back(guarded(own_words.back()));
        }
        DeviceBatch arrays =
            d.bind(instances, tight, {own[0], own[1], tangents ? own[2] : cl::Buffer(), {}});
        EXPECT_EQ(internal::streams_outputs(d, arrays), streams);
        DeviceBatch padded = d.allocate(instances, arrays_of(4, 0));
        EXPECT_FALSE(internal::streams_outputs(d, padded));
        const DeformedBatch<float> want =
            test::run_on_device(d, padded, values, NormalMode::kJacobian);
        test::expect_same_outputs(test::run_on_device(d, structs, values, NormalMode::kJacobian),
                                  want);
        test::expect_same_outputs(test::run_on_device(d, arrays, values, NormalMode::kJacobian),
                                  want);
        expect_guards(one, run.lead, words);
        for (std::size_t k = 0; k < own.size(); ++k) expect_guards(own[k], run.lead, own_words[k]);
      }
    }
  }
}

// The whole-body bend in mesh order (its slots are its vertices: slot order without the
// padding): a vertex struct in one buffer and attributes in arrays of their own are
// stored as vectors by every lane count, the work-item that reaches past the last vertex
// storing only its vertices (FF_OUTPUT_LIMIT). Each vertex holds the same bits as the same
// deformer writes in slot order, and nothing is written past the last vertex of the last
// instance. Other layouts of the bend in mesh order take one lane. GPUs (one lane) stage
// the float32 struct through local memory in mesh order too, and store the others
// attribute by attribute: the same checks.
LANES_TEST(TheBendInMeshOrderStoresStructsAndArraysAsVectors) {
  const bool gpu = test::shared_context().description().is_gpu();
  const RiggedMesh bend = blub_exact_bend();
  const Mesh barramundi = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh bend_with_tangents =
      RiggedMesh::single_bend(barramundi, find_body_frame(barramundi), BendMode::kExact);
  using F = AttributeFormat;
  struct Case {
    const char* name;
    F position, normal, tangent;
    bool one_buffer;
  };
  for (const RiggedMesh* model : {&bend, &bend_with_tangents}) {
    const std::size_t vertices = model->vertex_count();
    ASSERT_NE(vertices % 32, 0u);  // a work-item reaches past the last vertex
    const bool tangents = model->mesh().has_tangents();
    const RigParameters values = test::bend_fractions(*model, {0.9, -0.4, 0.6});
    const std::size_t instances = values.instance_count();
    for (const Case& c :
         {Case{"interleaved float32", F::kFloat32x3, F::kFloat32x3, F::kFloat32x3, true},
          Case{"compact", F::kFloat32x3, F::kOctahedral16x2, F::kOctahedral16x2, true},
          Case{"snorm16, float32x4", F::kFloat32x4, F::kSnorm16x4, F::kSnorm16x4, true},
          Case{"arrays", F::kFloat32x3, F::kFloat32x3, F::kFloat32x4, false},
          Case{"arrays, float16x4", F::kFloat32x3, F::kFloat16x4, F::kFloat16x4, false}}) {
      for (std::size_t lanes : gpu ? std::vector<std::size_t>{1} : vector_lanes()) {
        SCOPED_TRACE(testing::Message() << (tangents ? "Barramundi, " : "Blub, ") << c.name << ", "
                                        << lanes << " lanes");
        ClDeformer d(test::shared_context(), *model, with_lanes(lanes));
        auto layout_in = [&](VertexOrder order) {
          const std::size_t n = d.output_vertices(order);
          const std::size_t stride = format_bytes(c.position) + format_bytes(c.normal) +
                                     (tangents ? format_bytes(c.tangent) : 0);
          OutputLayout l;
          l.order = order;
          std::size_t at = 0;
          auto next = [&](AttributeFormat format) {
            const AttributeLayout a = c.one_buffer ? AttributeLayout::packed(format, n, stride, at)
                                                   : AttributeLayout::packed(format, n);
            at += format_bytes(format);
            return a;
          };
          l.positions = next(c.position);
          l.normals = next(c.normal);
          if (tangents) l.tangents = next(c.tangent);
          return l;
        };
        const OutputLayout mesh = layout_in(VertexOrder::kMesh);
        EXPECT_EQ(internal::lanes(d, mesh), lanes);
        // Each buffer as long as its attributes need, and 64 words of -7 after them.
        std::vector<std::size_t> bytes;
        std::vector<cl::Buffer> buffers;
        const AttributeLayout* tangent = mesh.written()[2];
        for (const AttributeLayout* a : {&mesh.positions, &mesh.normals, tangent}) {
          if ((c.one_buffer && !buffers.empty()) || a == nullptr) break;
          bytes.push_back(OutputLayout::required_bytes(
              c.one_buffer ? (tangent ? *tangent : mesh.normals) : *a, instances, vertices));
          std::vector<float> filled(bytes.back() / 4 + 64, -7.0f);
          cl_int status = CL_SUCCESS;
          buffers.emplace_back(test::shared_context().context(),
                               CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                               filled.size() * sizeof(float), filled.data(), &status);
          check_cl(status, "clCreateBuffer");
        }
        auto buffer = [&](std::size_t k) { return c.one_buffer ? buffers[0] : buffers[k]; };
        DeviceBatch in_mesh_order = d.bind(
            instances, mesh, {buffer(0), buffer(1), tangents ? buffer(2) : cl::Buffer(), {}});
        DeviceBatch in_slots = d.allocate(instances, layout_in(VertexOrder::kSlots));
        const DeformedBatch<float> got =
            test::run_on_device(d, in_mesh_order, values, NormalMode::kJacobian);
        const DeformedBatch<float> want =
            test::run_on_device(d, in_slots, values, NormalMode::kJacobian);
        for (std::size_t i = 0; i < instances; ++i) {
          for (std::size_t v = 0; v < vertices; ++v) {
            ASSERT_EQ(got.position(i, v), want.position(i, v)) << i << " " << v;
            ASSERT_EQ(got.normal(i, v), want.normal(i, v)) << i << " " << v;
            if (tangents) {
              ASSERT_EQ(got.tangent(i, v), want.tangent(i, v)) << i << " " << v;
            }
          }
        }
        for (std::size_t k = 0; k < buffers.size(); ++k) {
          std::vector<float> after(bytes[k] / 4 + 64);
          check_cl(test::shared_context().queue().enqueueReadBuffer(
                       buffers[k], CL_TRUE, 0, after.size() * sizeof(float), after.data()),
                   "clEnqueueReadBuffer");
          for (std::size_t w = bytes[k] / 4; w < after.size(); ++w) {
            ASSERT_EQ(after[w], -7.0f) << w;
          }
        }
      }
    }
  }
  if (gpu) return;
  // Planes in mesh order: one lane.
  ClDeformer sixteen(test::shared_context(), bend, with_lanes(16));
  OutputLayout planes = sixteen.layout(3);
  planes.order = VertexOrder::kMesh;
  planes.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, bend.vertex_count());
  planes.normals = planes.positions;
  EXPECT_EQ(internal::lanes(sixteen, planes), 1u);
}

// OutputStores::kAuto streams a frame's outputs only when they are larger than the
// caches could hold: the device's global memory cache (CL_DEVICE_GLOBAL_MEM_CACHE_SIZE),
// at most 4 MiB per compute unit (ClTuning::stores); kPlain and kStreaming are what
// they say; one lane never streams.
TEST(Lanes, AutomaticStoresStreamOutputsLargerThanTheCache) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  const DeviceDescription& device = test::shared_context().description();
  const std::size_t cache = std::min(device.global_memory_cache_bytes,
                                     std::max<std::size_t>(device.compute_units, 1) * (4u << 20));
  ClDeformer automatic(test::shared_context(), model, with_lanes(16));
  // A batch's size as its shape says (streams_outputs allocates nothing; a batch that
  // large would be the cache's size).
  DeviceBatch batch = automatic.allocate(1);
  const std::size_t per_instance = batch.shape.plane_stride * batch.shape.bytes_per_vertex();
  const std::size_t fitting = std::max<std::size_t>(1, cache / per_instance);
  batch.shape.instance_count = fitting;
  if (fitting * per_instance <= cache) {
    EXPECT_FALSE(internal::streams_outputs(automatic, batch));
  }
  batch.shape.instance_count = cache / per_instance + 1;
  EXPECT_TRUE(internal::streams_outputs(automatic, batch));
  ClTuning plain = with_lanes(16), streaming = with_lanes(16);
  plain.stores = OutputStores::kPlain;
  streaming.stores = OutputStores::kStreaming;
  const DeviceBatch small = automatic.allocate(1);
  EXPECT_FALSE(internal::streams_outputs(ClDeformer(test::shared_context(), model, plain), small));
  EXPECT_TRUE(
      internal::streams_outputs(ClDeformer(test::shared_context(), model, streaming), small));
  streaming.lanes = 1;
  EXPECT_FALSE(
      internal::streams_outputs(ClDeformer(test::shared_context(), model, streaming), small));
}

// Expects `half` to hold `full`'s positions and its directions rounded to the nearest
// half (the bits of a half read back as floats are their own nearest half).
void expect_rounded_to_half(const DeformedBatch<float>& half, const DeformedBatch<float>& full) {
  EXPECT_EQ(half.positions, full.positions);
  const std::vector<float>* pairs[][2] = {{&half.normals, &full.normals},
                                          {&half.tangents, &full.tangents}};
  for (const auto& pair : pairs) {
    ASSERT_EQ(pair[0]->size(), pair[1]->size());
    for (std::size_t k = 0; k < pair[0]->size(); ++k) {
      ASSERT_EQ(test::nearest_half((*pair[0])[k]), test::nearest_half((*pair[1])[k]))
          << "element " << k << ": " << (*pair[1])[k] << " -> " << (*pair[0])[k];
    }
  }
}

// Half-precision normals and tangents in FinFlex's planes take the lanes too
// (kernels/cpu/lane_planes.cl store_half_lanes; its rounding against the format's
// definition: test_normal_format's EveryHalfStoreWritesTheNearestHalf): with every lane
// count, on both paths and in both normal modes, the same deformer's float32 positions
// and its directions rounded to the nearest half; streamed, plain, and into a caller's
// host memory that is not aligned to the vectors, the same bits.
LANES_TEST(HalfNormalPlanesTakeLanesAndRoundTheFloat32Outputs) {
  const RiggedMesh model = barramundi_swim();
  ASSERT_TRUE(model.mesh().has_tangents());
  const RigParameters values = swimming_values(model, 5);
  const std::size_t instances = values.instance_count();
  for (std::size_t lanes : vector_lanes()) {
    ClTuning streaming = with_lanes(lanes), plain = with_lanes(lanes);
    streaming.stores = OutputStores::kStreaming;
    plain.stores = OutputStores::kPlain;
    ClDeformer streamed(test::shared_context(), model, streaming);
    ClDeformer unstreamed(test::shared_context(), model, plain);
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
        SCOPED_TRACE(std::to_string(lanes) + " lanes, " + to_string(normals) + ", " +
                     to_string(path));
        DeviceBatch batch = streamed.allocate(instances, NormalFormat::kHalf);
        EXPECT_EQ(internal::lanes(streamed, batch.outputs), lanes);
        const DeformedBatch<float> half =
            test::run_on_device(streamed, batch, values, normals, path);
        expect_rounded_to_half(half, test::run_on_device(streamed, values, normals, path));
        test::expect_same_outputs(
            test::run_on_device(unstreamed, values, normals, path, false, NormalFormat::kHalf),
            half);
      }
    }
    // A caller's host memory one float past a vector boundary (host memory is aligned
    // to a float at least: the kernels take every output buffer as floats): the
    // unaligned stores.
    DeviceBatch unaligned = streamed.allocate(instances, NormalFormat::kHalf);
    const std::size_t elements = unaligned.shape.attribute_elements();
    std::vector<std::vector<std::uint16_t>> memory(3,
                                                   std::vector<std::uint16_t>(2 * elements + 32));
    cl::Buffer* buffers[] = {&unaligned.positions, &unaligned.normals, &unaligned.tangents};
    const std::size_t bytes[] = {elements * sizeof(float), elements * 2, elements * 2};
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint16_t* first = memory[k].data() + 2;
      ASSERT_NE(reinterpret_cast<std::uintptr_t>(first) % 64, 0u);
      *buffers[k] =
          cl::Buffer(test::shared_context().context(), CL_MEM_USE_HOST_PTR, bytes[k], first);
    }
    test::expect_same_outputs(
        test::run_on_device(streamed, unaligned, values, NormalMode::kRotate, RigPath::kFused),
        test::run_on_device(streamed, values, NormalMode::kRotate, RigPath::kFused, false,
                            NormalFormat::kHalf));
  }
}

}  // namespace
}  // namespace finflex

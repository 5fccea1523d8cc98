// The kernels build without a warning: every program variant the library builds, each
// built first with warnings shown and -Werror (FINFLEX_KERNEL_WARNINGS, set here for
// the whole program: engine/src/context.cpp), so that a warning fails the build with
// the build log as the error's message. The variants: the whole-body bend's kernel (the
// paper and the exact bend), rig kernels (bends and hinges; a spine with fins swept
// along it, and its rig_prepare) fused and in passes, both dispatches, one lane and
// vectors of 8, 16 and 32 lanes (32 on PoCL only) with plain and streaming stores,
// several instances per work-item, both normal modes, every output format, planes,
// packed arrays and vertex structs (staged and direct), mesh order, tangents, previous
// positions, world placement, the per-instance tables' work-items, and the swim
// driver. Small meshes: a variant's code does not depend on the mesh's size. The
// KernelWarningsLarge tests build all of them; the KernelWarnings ones, in the default
// run, the code each option adds at one lane and 16 with Jacobian normals (the rest take
// a CPU's OpenCL compiler minutes to build).
//
// On an NVIDIA GPU this checks its OpenCL C 1.2 compiler's warnings too (run the
// program there as scripts/device/gpu_checks.sh runs the others); 32 lanes are PoCL's
// only, and left out there.
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// Before the first build of the program: the library reads it at every build.
const bool warnings_fail = [] { return setenv("FINFLEX_KERNEL_WARNINGS", "1", 1) == 0; }();

bool device_is_pocl() {
  const std::string& platform = test::shared_context().description().platform_name;
  return platform.find("Portable Computing Language") != std::string::npos;
}

// The variants a run builds: the default run's (one lane and 16, Jacobian normals,
// streaming stores: the code each option adds) or every one (the large run's).
std::vector<std::size_t> lane_counts(bool every) {
  if (!every) return {1, 16};
  std::vector<std::size_t> lanes = {1, 8, 16};
  if (device_is_pocl()) lanes.push_back(32);
  return lanes;
}

std::vector<NormalMode> normal_modes(bool every) {
  if (!every) return {NormalMode::kJacobian};
  return {NormalMode::kRotate, NormalMode::kJacobian};
}

std::vector<OutputStores> stores_of(bool every) {
  if (!every) return {OutputStores::kStreaming};
  return {OutputStores::kPlain, OutputStores::kStreaming};
}

// TEST(KernelWarnings, NAME) with the default run's variants, and
// TEST(KernelWarningsLarge, NAME) with every one (a large test: tests/CMakeLists.txt).
#define KERNEL_WARNINGS_TEST(name)                         \
  void name##_builds(bool every);                          \
  TEST(KernelWarnings, name) { name##_builds(false); }     \
  TEST(KernelWarningsLarge, name) { name##_builds(true); } \
  void name##_builds(bool every)

RiggedMesh shipped(const char* mesh_file, const char* rig_file) {
  const Mesh mesh = load_mesh(test::data_path(mesh_file));
  return RiggedMesh(mesh, resolve_rig(load_rig_file(test::data_path(rig_file)), mesh));
}

// Two instances through `deformer` into `batch` (and the frame after, for previous
// positions), placed when `placed`: any failed build throws, naming the log.
void run(ClDeformer& deformer, DeviceBatch& batch, NormalMode normals, RigPath path,
         bool placed = false) {
  const RigParameters values = test::at_fractions_of_the_limits(deformer.model(), {0.5, -0.3});
  std::vector<Placement> where(2);
  where[1].position = glm::vec3(1.0f, 0.0f, 0.5f);
  for (int frame = 0; frame < (batch.outputs.previous_positions ? 2 : 1); ++frame) {
    EXPECT_NO_THROW(test::run_on_device(deformer, batch, values, normals, path, false,
                                        placed ? where.data() : nullptr));
  }
}

void run_planes(ClDeformer& deformer, NormalFormat format, NormalMode normals, RigPath path,
                bool placed = false) {
  DeviceBatch batch = deformer.allocate(2, format);
  run(deformer, batch, normals, path, placed);
}

ClTuning options_of(std::size_t lanes, OutputStores stores = OutputStores::kAuto,
                    std::size_t per_item = 0) {
  ClTuning options;
  options.lanes = lanes;
  options.stores = stores;
  options.instances_per_item = per_item;
  return options;
}

// Every output format of positions, normals and tangents, as packed arrays and as one
// vertex struct, in slot and in mesh order, with previous positions or without.
std::vector<OutputLayout> layouts(const ClDeformer& deformer) {
  using F = AttributeFormat;
  const bool tangents = deformer.model().mesh().has_tangents();
  std::vector<OutputLayout> out;
  struct Formats {
    F position, normal;
  };
  for (VertexOrder order : {VertexOrder::kSlots, VertexOrder::kMesh}) {
    const std::size_t vertices = deformer.output_vertices(order);
    // Half normals of three components in arrays of their own (a struct of them would
    // leave its members off the 4-byte words).
    OutputLayout halves;
    halves.order = order;
    halves.positions = AttributeLayout::packed(F::kFloat32x3, vertices);
    halves.normals = AttributeLayout::packed(F::kFloat16x3, vertices);
    if (tangents) halves.tangents = AttributeLayout::packed(F::kFloat16x3, vertices);
    out.push_back(halves);
    for (const Formats& f :
         {Formats{F::kFloat32x3, F::kFloat32x3}, Formats{F::kFloat32x4, F::kFloat16x4},
          Formats{F::kFloat32x3, F::kSnorm16x4}, Formats{F::kFloat32x3, F::kOctahedral16x2}}) {
      // Arrays of their own.
      OutputLayout arrays;
      arrays.order = order;
      arrays.positions = AttributeLayout::packed(f.position, vertices);
      arrays.normals = AttributeLayout::packed(f.normal, vertices);
      if (tangents) arrays.tangents = AttributeLayout::packed(f.normal, vertices);
      out.push_back(arrays);
      // One vertex struct.
      const std::size_t stride =
          format_bytes(f.position) + (tangents ? 2 : 1) * format_bytes(f.normal);
      OutputLayout structs = arrays;
      structs.positions = AttributeLayout::packed(f.position, vertices, stride, 0);
      structs.normals =
          AttributeLayout::packed(f.normal, vertices, stride, format_bytes(f.position));
      if (tangents) {
        structs.tangents = AttributeLayout::packed(
            f.normal, vertices, stride, format_bytes(f.position) + format_bytes(f.normal));
      }
      out.push_back(structs);
    }
    OutputLayout previous;
    previous.order = order;
    previous.positions = AttributeLayout::packed(F::kFloat32x3, vertices);
    previous.normals = AttributeLayout::packed(F::kFloat32x3, vertices);
    if (tangents) previous.tangents = previous.normals;
    previous.previous_positions = AttributeLayout::packed(F::kFloat32x4, vertices);
    out.push_back(previous);
  }
  return out;
}

// The layouts through `options`' kernels, in normal_modes(every).
void run_layouts(const RiggedMesh& model, const ClTuning& options, RigPath path, bool every) {
  ClDeformer deformer(test::shared_context(), model, options);
  for (const OutputLayout& layout : layouts(deformer)) {
    for (NormalMode normals : normal_modes(every)) {
      SCOPED_TRACE(testing::Message() << to_string(layout.order) << " " << to_string(normals) << " "
                                      << options.lanes << " lanes");
      DeviceBatch batch = deformer.allocate(2, layout);
      run(deformer, batch, normals, path);
    }
  }
}

// A program of the caller's own (ProgramSource::appended) that warns: with
// FINFLEX_KERNEL_WARNINGS its build fails, naming the warning; without, it builds and
// nothing reaches stderr (where PoCL's clang would count the warnings).
TEST(KernelWarnings, AWarningFailsTheBuildHereAndIsSilentElsewhere) {
  ASSERT_TRUE(warnings_fail);
  Context& context = test::shared_context();
  const ProgramSource warns{{}, "", "#warning a deliberate warning\n__kernel void warns() {}\n"};
  try {
    context.program(warns, "-DFF_TEST_WARNS=1");
    ADD_FAILURE() << "a warning did not fail the build";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOpenCL);
    EXPECT_NE(std::string(e.what()).find("a deliberate warning"), std::string::npos) << e.what();
  }
  unsetenv("FINFLEX_KERNEL_WARNINGS");
  testing::internal::CaptureStderr();
  EXPECT_NO_THROW(context.kernel("warns", warns, "-DFF_TEST_WARNS=2"));
  const std::string printed = testing::internal::GetCapturedStderr();
  setenv("FINFLEX_KERNEL_WARNINGS", "1", 1);
  EXPECT_EQ(printed, "");
}

KERNEL_WARNINGS_TEST(NoneInTheWholeBodyBend) {
  const Mesh mesh = test::synthetic_fish(6, 6, true);
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), mode);
    for (std::size_t lanes : lane_counts(every)) {
      for (OutputStores stores : stores_of(every)) {
        if (lanes == 1 && stores == OutputStores::kStreaming && every) continue;
        ClDeformer deformer(test::shared_context(), bend, options_of(lanes, stores));
        for (NormalFormat format : {NormalFormat::kFloat32, NormalFormat::kHalf}) {
          for (NormalMode normals : normal_modes(every)) {
            SCOPED_TRACE(testing::Message()
                         << to_string(mode) << " " << lanes << " lanes " << to_string(normals));
            run_planes(deformer, format, normals, RigPath::kAuto);
            run_planes(deformer, format, normals, RigPath::kAuto, /*placed=*/true);
          }
        }
      }
    }
    // Several instances a work-item, and the bend as a rig like any other.
    ClDeformer several(test::shared_context(), bend, options_of(1, OutputStores::kAuto, 2));
    run_planes(several, NormalFormat::kHalf, NormalMode::kRotate, RigPath::kAuto);
    ClTuning as_rig;
    as_rig.single_bend_kernel = false;
    ClDeformer rig(test::shared_context(), bend, as_rig);
    run_planes(rig, NormalFormat::kFloat32, NormalMode::kJacobian, RigPath::kFused);
  }
}

// Every output layout (layouts()): one lane and 16, and a staged vertex struct; the
// default run, those of one lane and Jacobian normals.
KERNEL_WARNINGS_TEST(NoneInTheWholeBodyBendsLayouts) {
  const Mesh mesh = test::synthetic_fish(6, 6, true);
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  run_layouts(bend, options_of(1), RigPath::kAuto, every);
  if (!every) return;
  run_layouts(bend, options_of(16), RigPath::kAuto, every);
  ClTuning staged = options_of(1);
  staged.struct_stores = ClTuning::StructStores::kStaged;
  run_layouts(bend, staged, RigPath::kAuto, every);
}

KERNEL_WARNINGS_TEST(NoneInTheRigKernels) {
  const RiggedMesh rig =
      shipped("blub/fish_low_resolution.obj", "rigs/blub_low_resolution.rig.json");
  for (std::size_t lanes : lane_counts(every)) {
    for (RigDispatch dispatch : {RigDispatch::kPerComponent, RigDispatch::kByPathShape}) {
      ClTuning options = options_of(lanes);
      options.dispatch = dispatch;
      ClDeformer deformer(test::shared_context(), rig, options);
      for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
        for (NormalMode normals : normal_modes(every)) {
          SCOPED_TRACE(testing::Message()
                       << lanes << " lanes " << to_string(path) << " " << to_string(normals));
          run_planes(deformer, NormalFormat::kFloat32, normals, path);
          run_planes(deformer, NormalFormat::kHalf, normals, path, /*placed=*/true);
        }
      }
    }
  }
  ClDeformer several(test::shared_context(), rig, options_of(1, OutputStores::kAuto, 4));
  run_planes(several, NormalFormat::kHalf, NormalMode::kJacobian, RigPath::kFused);
  if (!every) return;
  run_layouts(rig, options_of(1), RigPath::kFused, every);
  run_layouts(rig, options_of(16, OutputStores::kStreaming), RigPath::kPasses, every);
}

KERNEL_WARNINGS_TEST(NoneInTheSpineAndSweptFins) {
  const RiggedMesh swim =
      shipped("blub/fish_low_resolution.obj", "rigs/blub_low_resolution_swim.rig.json");
  for (std::size_t lanes : lane_counts(every)) {
    for (std::size_t table_items : {std::size_t{1}, std::size_t{8}}) {
      if (table_items == 8 && !every) continue;
      ClTuning options = options_of(lanes);
      options.table_items = table_items;
      ClDeformer deformer(test::shared_context(), swim, options);
      for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
        for (NormalMode normals : normal_modes(every)) {
          SCOPED_TRACE(testing::Message()
                       << lanes << " lanes " << to_string(path) << " " << to_string(normals));
          run_planes(deformer, NormalFormat::kFloat32, normals, path, /*placed=*/true);
        }
      }
    }
  }
  if (!every) return;
  ClTuning per_component = options_of(1, OutputStores::kAuto, 8);
  per_component.dispatch = RigDispatch::kPerComponent;
  per_component.table_items = 8;
  ClDeformer deformer(test::shared_context(), swim, per_component);
  run_planes(deformer, NormalFormat::kHalf, NormalMode::kJacobian, RigPath::kFused);
}

TEST(KernelWarnings, NoneInTheSwimDriver) {
  const RiggedMesh model =
      shipped("blub/fish_low_resolution.obj", "rigs/blub_low_resolution_swim.rig.json");
  const SwimModel swim(model);
  {
    for (std::size_t fish : {std::size_t{1}, std::size_t{40}}) {
      const std::vector<float> lengths(fish, 0.3f);
      std::vector<SwimInput> inputs(fish);
      for (SwimInput& input : inputs) input.speed = 0.2f;
      ClSwimDriver driver(test::shared_context(), swim, lengths);
      EXPECT_NO_THROW(driver.enqueue(inputs, 1.0f / 30.0f).wait());
    }
  }
}

}  // namespace
}  // namespace finflex

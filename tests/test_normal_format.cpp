// Half-precision normals and tangents (NormalFormat::kHalf): 18 bytes per vertex
// instead of 24. Positions stay float32 and bit-identical; normals and tangents round
// to IEEE half, relative error 2^-11 per component, so unit vectors differ from the
// float32 ones by under 1e-3.
//
// The GPU-only code is run here on any device: the half store of GPUs (vstore_half,
// FF_GPU=1) and of CPUs (half_bits) both against the nearest half computed on the
// host, and the GPUs' shapes (four instances per work-item, stages compiled in per
// component) forced through ClTuning.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
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
      if (full.shape.tangents) {
        ASSERT_LT(glm::length(full.tangent(i, v) - half.tangent(i, v)), 1e-3f) << "vertex " << v;
        expect_nearest_half(full.tangent(i, v), half.tangent(i, v), v);
      }
    }
  }
}

TEST(NormalFormat, LayoutBytesAndNames) {
  BatchShape layout;
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
  EXPECT_EQ(half.shape.normal_format, NormalFormat::kHalf);
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
  ASSERT_EQ(internal::pass_count(deformer), 5u);
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

TEST(NormalFormat, EveryHalfStoreWritesTheNearestHalf) {
  // kernels/common/outputs.cl's store of float16x3 planes in a kernel of the test's own, built
  // once with the GPUs' branch (vstore_half) and once with the CPUs' (half_bits),
  // whatever the device, and on CPUs the store of kernels of 8, 16 and 32 lanes (32 on
  // PoCL: kernels/cpu/lane_outputs.cl, half_bits on vectors): values across [-1, 1]
  // with ties between two halves, values that become subnormal halves, zeros of both
  // signs, the largest half and what rounds past it (infinity).
  std::vector<float> values = {0.0f,
                               -0.0f,
                               1.0f,
                               -1.0f,
                               0.5f,
                               1e-8f,
                               -3e-8f,
                               6e-8f,
                               1e-5f,
                               -6.1e-5f,
                               0.33333334f,
                               -0.7071068f,
                               65504.0f,
                               -65519.0f,
                               65520.0f,
                               -1e10f,
                               std::numeric_limits<float>::infinity()};
  // Exact ties: half-way between two neighbouring halves in [0.5, 1) (spacing 2^-11),
  // with an even and an odd lower neighbour, both signs.
  for (int k : {0, 1, 2, 3, 100, 101, 1022}) {
    const float tie = std::ldexp(1024.0f + float(k) + 0.5f, -11);
    values.push_back(tie);
    values.push_back(-tie);
  }
  for (int k = 0; k < 200; ++k) values.push_back(std::sin(0.37f * float(k)));
  while (values.size() % 64) values.push_back(0.25f);
  // A block of normal halves only, ties among them: whole vectors of the lanes' store
  // with no zero, subnormal or special value.
  for (int k = 0; k < 64; ++k) {
    const float tie = std::ldexp(1024.0f + float(3 * k) + 0.5f, -11 - k % 9);
    values.push_back(k % 2 ? tie : -tie);
  }
  const std::size_t stride = values.size();
  // One vector per slot: x, y and z take the values rotated by 0, 1 and 2 slots.
  std::vector<float> planes(3 * stride);
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t v = 0; v < stride; ++v) planes[c * stride + v] = values[(v + c) % stride];
  }
  ProgramSource source;
  source.files = common_kernel_files();
  source.appended = R"(
__kernel void store_halves(__global const float* in, __global float* out, const uint stride) {
  /* Instance 1 of float16x3 planes of `stride` halves. */
#if FF_LANES == 1
  const size_t v = get_global_id(0);
  store_attribute(out, FF_F16X3, 0, 0, stride, 3 * stride, 1, v, load_plane3(in, 0, stride, v), 0.0f);
#else
  const size_t v = FF_FIRST_SLOT;
  store_lane_attribute(out, FF_F16X3, 0, stride, 3 * stride, 1, v, load_plane3(in, 0, stride, v),
                       FF_LANES);
#endif
}
)";
  Context& context = test::shared_context();
  // software: FF_SOFTWARE_HALF, the integer rounding that CPUs without a conversion
  // instruction take (common/planes.cl), where the others convert in hardware.
  struct Store {
    const char* name;
    int gpu;
    std::size_t lanes;
    int software;
  };
  std::vector<Store> stores = {{"vstore_half (GPUs)", 1, 1, 0},
                               {"half_bits (CPUs)", 0, 1, 0},
                               {"half_bits in software", 0, 1, 1}};
  if (!context.description().is_gpu()) {
    stores.insert(stores.end(), {{"8 lanes", 0, 8, 0},
                                 {"16 lanes", 0, 16, 0},
                                 {"8 lanes in software", 0, 8, 1},
                                 {"16 lanes in software", 0, 16, 1}});
    if (context.description().platform_name.find("Portable Computing Language") !=
        std::string::npos) {
      stores.push_back({"32 lanes", 0, 32, 0});
    }
  }
  for (const Store& store : stores) {
    SCOPED_TRACE(store.name);
    // The device's FF_GPU comes as a build option; the source replaces it before
    // planes.cl reads it.
    source.generated = "#undef FF_GPU\n#define FF_GPU " + std::to_string(store.gpu) + "\n";
    cl::Kernel kernel = context.kernel("store_halves", source,
                                       "-DFF_LANES=" + std::to_string(store.lanes) +
                                           " -DFF_SOFTWARE_HALF=" + std::to_string(store.software));
    cl_int status = CL_SUCCESS;
    cl::Buffer in(context.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                  planes.size() * sizeof(float), planes.data(), &status);
    check_cl(status, "clCreateBuffer");
    // Two instances' planes of halves: the kernel writes the second instance's (planes
    // 3-5), the first must stay as it was (0xFFFF, a NaN no store writes).
    std::vector<std::uint16_t> halves(6 * stride, 0xffff);
    cl::Buffer out(context.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                   halves.size() * sizeof(std::uint16_t), halves.data(), &status);
    check_cl(status, "clCreateBuffer");
    check_cl(kernel.setArg(0, in), "clSetKernelArg");
    check_cl(kernel.setArg(1, out), "clSetKernelArg");
    check_cl(kernel.setArg(2, static_cast<cl_uint>(stride)), "clSetKernelArg");
    check_cl(context.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                                  cl::NDRange(stride / store.lanes),
                                                  cl::NDRange(64 / store.lanes)),
             "clEnqueueNDRangeKernel");
    check_cl(context.queue().enqueueReadBuffer(
                 out, CL_TRUE, 0, halves.size() * sizeof(std::uint16_t), halves.data()),
             "clEnqueueReadBuffer");
    for (std::size_t at = 0; at < 3 * stride; ++at) ASSERT_EQ(halves[at], 0xffff) << at;
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t v = 0; v < stride; ++v) {
        const float value = planes[c * stride + v];
        ASSERT_EQ(halves[(3 + c) * stride + v], test::nearest_half(value))
            << "component " << c << " slot " << v << ": " << value;
      }
    }
  }
}

// The shapes GPUs take by default, forced on this device: four instances per work-item
// for half normals (single bend and rigs) and stages compiled in per component for
// rigs. They must write what one instance per work-item writes (positions to float32
// rounding: the compiler may contract multiply-adds differently; halves within one
// rounding of each other's float value).
TEST(NormalFormat, HalfNormalsInTheShapesGpusTake) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));  // has tangents
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  const RiggedMesh rig(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh));
  for (const RiggedMesh* model : {&bend, &rig}) {
    const RigParameters values =
        test::at_fractions_of_the_limits(*model, {0.3, -0.6, 0.9, 0.1, -0.2});
    ClTuning one;
    one.instances_per_item = 1;
    one.dispatch = RigDispatch::kByPathShape;
    ClTuning gpu_shape;
    gpu_shape.instances_per_item = 4;
    gpu_shape.dispatch = RigDispatch::kPerComponent;
    ClDeformer expected_deformer(test::shared_context(), *model, one);
    ClDeformer gpu_deformer(test::shared_context(), *model, gpu_shape);
    const BodyFrame& root = model->rig().components.front().frame;
    const double scale = glm::length(root.origin) + root.length;
    for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
      if (model == &bend && path == RigPath::kPasses) continue;
      for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
        // Rigs: one normal mode (each is its own set of kernels to build per rig).
        if (model == &rig && normals == NormalMode::kRotate) continue;
        SCOPED_TRACE(std::string(model == &bend ? "bend " : "rig ") + to_string(path) + " " +
                     to_string(normals));
        const DeformedBatch<float> full =
            test::run_on_device(expected_deformer, values, normals, path);
        const DeformedBatch<float> half =
            test::run_on_device(gpu_deformer, values, normals, path, false, NormalFormat::kHalf);
        for (std::size_t i = 0; i < values.instance_count(); ++i) {
          for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
            ASSERT_LT(
                glm::length(glm::dvec3(full.position(i, v)) - glm::dvec3(half.position(i, v))),
                1e-6 * scale)
                << "instance " << i << " vertex " << v;
            // One half rounding (2^-12 per component of a unit vector) plus float noise.
            ASSERT_LT(glm::length(full.normal(i, v) - half.normal(i, v)), 1e-3f)
                << "instance " << i << " vertex " << v;
            ASSERT_LT(glm::length(full.tangent(i, v) - half.tangent(i, v)), 1e-3f)
                << "instance " << i << " vertex " << v;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace finflex

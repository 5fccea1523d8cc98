// Hand-off (finflex/output_layout.hpp, ClDeformer::allocate/bind/bind_host): every
// format and arrangement written by the kernels decodes to the default planes within
// the format's precision, interleaved and separate arrays hold the same data, mesh
// order writes no padding, previous positions are the frame before, host memory is
// written in place on CPU devices, and bad bindings are named with nothing written.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// The Barramundi with its rig (fins: components, padding slots) and its tangents.
const RiggedMesh& barramundi() {
  static const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  static const RiggedMesh model(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh));
  return model;
}

ClDeformer& deformer() {
  static ClDeformer d(test::shared_context(), barramundi());
  return d;
}

constexpr std::size_t kInstances = 3;

RigParameters frame_values(double scale) {
  return test::at_fractions_of_the_limits(barramundi(), {0.7 * scale, -0.4 * scale, 0.9 * scale});
}

cl::Buffer device_buffer(std::size_t bytes, unsigned char fill = 0xAB) {
  std::vector<unsigned char> bytes_in(bytes, fill);
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(test::shared_context().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                    bytes, bytes_in.data(), &status);
  check_cl(status, "clCreateBuffer");
  return buffer;
}

std::vector<unsigned char> raw(const cl::Buffer& buffer) {
  std::size_t bytes = 0;
  buffer.getInfo(CL_MEM_SIZE, &bytes);
  std::vector<unsigned char> out(bytes);
  check_cl(test::shared_context().queue().enqueueReadBuffer(buffer, CL_TRUE, 0, bytes, out.data()),
           "clEnqueueReadBuffer");
  return out;
}

DeformedBatch<float> run(DeviceBatch& batch, const RigParameters& values) {
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = NormalMode::kJacobian;
  job.outputs = &batch;
  deformer().enqueue(job);
  return deformer().read(batch);
}

// The default planes' outputs of `values`: the reference of every layout.
DeformedBatch<float> planes_of(const RigParameters& values) {
  DeviceBatch planes = deformer().allocate(kInstances);
  return run(planes, values);
}

// The largest error of a decoded direction against float32: componentwise, or as an
// angle for the octahedral encoding (unit vectors compared after normalising).
double direction_error(const glm::vec3& got, const glm::vec3& want, AttributeFormat format) {
  if (format == AttributeFormat::kOctahedral16x2) {
    const double cosine =
        glm::dot(glm::normalize(glm::dvec3(got)), glm::normalize(glm::dvec3(want)));
    return std::acos(std::min(1.0, cosine));
  }
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::fabs(double(got[c]) - double(want[c])));
  return e;
}

// The documented precision of each format (docs/handoff.md): float32 exact; halves
// 2^-11 relative on values within 1 (2^-12 absolute after rounding, on [-1, 1]);
// snorm16 half a step, 0.5 / 32767; octahedral 16-bit pairs, 7e-5 rad (its largest
// error over 2 million random directions, in double, is 6.4e-5 rad).
double bound(AttributeFormat format) {
  switch (format) {
    case AttributeFormat::kFloat32x3:
    case AttributeFormat::kFloat32x4:
      return 0.0;
    case AttributeFormat::kFloat16x3:
    case AttributeFormat::kFloat16x4:
      return std::ldexp(1.0, -12);
    case AttributeFormat::kSnorm16x4:
      return 0.5 / 32767.0 + 1e-7;
    case AttributeFormat::kOctahedral16x2:
      return 7e-5;
  }
  return 0.0;
}

void expect_matches(const DeformedBatch<float>& got, const DeformedBatch<float>& want,
                    const OutputLayout& layout, const char* what) {
  SCOPED_TRACE(what);
  const std::size_t vertices = barramundi().vertex_count();
  double position = 0.0, normal = 0.0, tangent = 0.0;
  for (std::size_t i = 0; i < kInstances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      position = std::max(position, double(glm::length(got.position(i, v) - want.position(i, v))));
      normal = std::max(
          normal, direction_error(got.normal(i, v), want.normal(i, v), layout.normals.format));
      if (layout.tangents) {
        tangent = std::max(tangent, direction_error(got.tangent(i, v), want.tangent(i, v),
                                                    layout.tangents->format));
      }
    }
  }
  testing::Test::RecordProperty(std::string(what) + " normal error", std::to_string(normal));
  testing::Test::RecordProperty(std::string(what) + " tangent error", std::to_string(tangent));
  EXPECT_EQ(position, 0.0);  // float32 positions: the same bits
  EXPECT_LE(normal, bound(layout.normals.format)) << to_string(layout.normals.format);
  if (layout.tangents) {
    EXPECT_LE(tangent, bound(layout.tangents->format)) << to_string(layout.tangents->format);
  }
  // Each format is actually rounded (not float32 underneath), except float32.
  if (layout.normals.format != AttributeFormat::kFloat32x3) {
    EXPECT_GT(normal, 0.0);
  }
}

// An interleaved vertex of 28 bytes: position float32x3 at 0, normal float16x4 at 12,
// tangent snorm16x4 at 20.
OutputLayout interleaved_layout(std::size_t vertices) {
  OutputLayout l;
  l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, 28, 0);
  l.normals = AttributeLayout::packed(AttributeFormat::kFloat16x4, vertices, 28, 12);
  l.tangents = AttributeLayout::packed(AttributeFormat::kSnorm16x4, vertices, 28, 20);
  return l;
}

// Its buffer: up to the last vertex's tangent.
std::size_t interleaved_bytes(const OutputLayout& l, std::size_t vertices) {
  return OutputLayout::required_bytes(*l.tangents, kInstances, vertices);
}

TEST(Handoff, EveryFormatDecodesToTheDefaultPlanesWithinItsPrecision) {
  const RigParameters values = frame_values(1.0);
  const DeformedBatch<float> want = planes_of(values);
  const std::size_t slots = deformer().output_vertices(VertexOrder::kSlots);
  const std::size_t mesh_vertices = deformer().output_vertices(VertexOrder::kMesh);
  EXPECT_GT(slots, mesh_vertices);  // the rig has padding slots

  // Interleaved, one buffer, slot order.
  {
    const OutputLayout l = interleaved_layout(slots);
    cl::Buffer one = device_buffer(interleaved_bytes(l, slots));
    DeviceBatch batch = deformer().bind(kInstances, l, {one, one, one, {}});
    expect_matches(run(batch, values), want, l, "interleaved float32x3 / float16x4 / snorm16x4");
    // The tangents' w is the rest mesh's handedness: +-32767 in snorm16.
    const std::vector<unsigned char> bytes = raw(one);
    const Mesh& mesh = barramundi().mesh();
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      std::int16_t w = 0;
      std::memcpy(&w, bytes.data() + deformer().slot_of_vertex()[v] * 28 + 20 + 6, 2);
      ASSERT_EQ(w, mesh.tangents[v].w < 0 ? -32767 : 32767) << "vertex " << v;
    }
  }
  // Separate arrays in one buffer, mesh order: float32x4 positions, octahedral
  // normals, float32x4 tangents.
  {
    OutputLayout l;
    l.order = VertexOrder::kMesh;
    l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x4, mesh_vertices);
    const std::size_t after_positions = kInstances * mesh_vertices * 16;
    l.normals = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, mesh_vertices, 0,
                                        after_positions);
    l.tangents = AttributeLayout::packed(AttributeFormat::kFloat32x4, mesh_vertices, 0,
                                         after_positions + kInstances * mesh_vertices * 4);
    const std::size_t bytes = OutputLayout::required_bytes(*l.tangents, kInstances, mesh_vertices);
    cl::Buffer one = device_buffer(bytes);
    DeviceBatch batch = deformer().bind(kInstances, l, {one, one, one, {}});
    expect_matches(run(batch, values), want, l, "arrays float32x4 / octahedral16x2 / float32x4");
    const std::vector<unsigned char> out = raw(one);
    const Mesh& mesh = barramundi().mesh();
    for (std::size_t i = 0; i < kInstances; ++i) {
      for (std::size_t v = 0; v < mesh_vertices; ++v) {
        float w_position = 0.0f, w_tangent = 0.0f;
        std::memcpy(&w_position, out.data() + (i * mesh_vertices + v) * 16 + 12, 4);
        std::memcpy(&w_tangent, out.data() + l.tangents->offset + (i * mesh_vertices + v) * 16 + 12,
                    4);
        ASSERT_EQ(w_position, 1.0f);
        ASSERT_EQ(w_tangent, mesh.tangents[v].w);
      }
    }
  }
  // Planes in mesh order, half normals in planes, float16x3 packed tangents.
  {
    OutputLayout l;
    l.order = VertexOrder::kMesh;
    l.positions = AttributeLayout::planes(AttributeFormat::kFloat32x3, mesh_vertices);
    l.normals = AttributeLayout::planes(AttributeFormat::kFloat16x3, mesh_vertices + 3);
    l.tangents = AttributeLayout::packed(AttributeFormat::kFloat16x3, mesh_vertices);
    DeviceBatch batch = deformer().allocate(kInstances, l);
    expect_matches(run(batch, values), want, l, "planes float32x3 / float16x3, packed float16x3");
  }
}

TEST(Handoff, InterleavedAndSeparateArraysHoldTheSameData) {
  const RigParameters values = frame_values(0.8);
  const std::size_t slots = deformer().output_vertices(VertexOrder::kSlots);
  const OutputLayout l = interleaved_layout(slots);
  cl::Buffer one = device_buffer(interleaved_bytes(l, slots));
  DeviceBatch interleaved = deformer().bind(kInstances, l, {one, one, one, {}});
  OutputLayout separate = l;
  separate.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots);
  separate.normals = AttributeLayout::packed(AttributeFormat::kFloat16x4, slots);
  separate.tangents = AttributeLayout::packed(AttributeFormat::kSnorm16x4, slots);
  DeviceBatch apart = deformer().allocate(kInstances, separate);
  const DeformedBatch<float> a = run(interleaved, values);
  const DeformedBatch<float> b = run(apart, values);
  test::expect_same_outputs(a, b);
}

// A vertex struct that its float32x3 attributes fill (tangent, position, normal: 36
// bytes; 24 without tangents), written through local memory (as GPUs do,
// ClTuning::struct_stores) and directly, holds exactly what the default planes hold:
// the single-bend kernel, and the rig's fused and multi-pass kernels.
TEST(Handoff, StagedVertexStructsHoldWhatThePlanesHold) {
  const Mesh blub = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh bend = RiggedMesh::single_bend(blub, find_body_frame(blub), BendMode::kExact);
  const RigParameters rig_values = frame_values(0.9);
  RigParameters bend_values(bend, kInstances);
  for (std::size_t i = 0; i < kInstances; ++i) bend_values.set(i, "m", 0.2f * float(i + 1));
  struct Case {
    const RiggedMesh* model;
    const RigParameters* values;
    RigPath path;
  };
  for (const Case& c : {Case{&bend, &bend_values, RigPath::kAuto},
                        Case{&barramundi(), &rig_values, RigPath::kFused},
                        Case{&barramundi(), &rig_values, RigPath::kPasses}}) {
    for (const auto stores : {ClTuning::StructStores::kStaged, ClTuning::StructStores::kDirect}) {
      SCOPED_TRACE(testing::Message() << "path " << to_string(c.path) << ", staged "
                                      << (stores == ClTuning::StructStores::kStaged));
      ClTuning options;
      options.struct_stores = stores;
      ClDeformer d(test::shared_context(), *c.model, options);
      const bool tangents = c.model->mesh().has_tangents();
      const std::size_t slots = d.output_vertices(VertexOrder::kSlots);
      const std::size_t stride = tangents ? 36 : 24;
      const std::size_t first = tangents ? 12 : 0;
      OutputLayout l;
      l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots, stride, first);
      l.normals = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots, stride, first + 12);
      if (tangents)
        l.tangents = AttributeLayout::packed(AttributeFormat::kFloat32x3, slots, stride, 0);
      cl::Buffer one = device_buffer(OutputLayout::required_bytes(l.normals, kInstances, slots));
      DeviceBatch structs = d.bind(kInstances, l, {one, one, one, {}});
      DeviceBatch planes = d.allocate(kInstances);
      ClJob job;
      job.instances = c.values->instance_count();
      job.parameters = c.values->view();
      job.normals = NormalMode::kJacobian;
      job.path = c.path;
      job.outputs = &structs;
      d.enqueue(job);
      const DeformedBatch<float> got = d.read(structs);
      job.outputs = &planes;
      d.enqueue(job);
      const DeformedBatch<float> want = d.read(planes);
      test::expect_same_outputs(got, want);
    }
  }
}

TEST(Handoff, MeshOrderWritesEveryVertexOnceAndNoPadding) {
  const RigParameters values = frame_values(0.6);
  const DeformedBatch<float> want = planes_of(values);
  const std::size_t vertices = deformer().output_vertices(VertexOrder::kMesh);
  OutputLayout l;
  l.order = VertexOrder::kMesh;
  l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices);
  l.normals = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices);
  l.tangents = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices);
  const std::size_t bytes = OutputLayout::required_bytes(l.positions, kInstances, vertices);
  EXPECT_EQ(bytes, kInstances * vertices * 12);
  // 256 bytes of sentinel past the end: padding slots must not land there.
  cl::Buffer positions = device_buffer(bytes + 256);
  cl::Buffer normals = device_buffer(bytes + 256);
  cl::Buffer tangents = device_buffer(bytes + 256);
  DeviceBatch batch = deformer().bind(kInstances, l, {positions, normals, tangents, {}});
  const DeformedBatch<float> got = run(batch, values);
  EXPECT_TRUE(got.slot_of_vertex.empty());  // mesh order: vertex v at v
  expect_matches(got, want, l, "mesh order");
  for (const cl::Buffer* buffer : {&positions, &normals, &tangents}) {
    const std::vector<unsigned char> out = raw(*buffer);
    for (std::size_t k = bytes; k < out.size(); ++k) ASSERT_EQ(out[k], 0xAB) << "byte " << k;
    // Every vertex written (no sentinel left inside).
    std::size_t untouched = 0;
    for (std::size_t k = 0; k + 4 <= bytes; k += 4) {
      std::uint32_t word = 0;
      std::memcpy(&word, out.data() + k, 4);
      untouched += word == 0xABABABABu;
    }
    EXPECT_EQ(untouched, 0u);
  }
}

TEST(Handoff, PreviousPositionsAreTheFrameBefore) {
  const std::size_t slots = deformer().output_vertices(VertexOrder::kSlots);
  OutputLayout l = deformer().layout(kInstances);
  l.previous_positions = AttributeLayout::packed(AttributeFormat::kFloat32x4, slots);
  DeviceBatch batch = deformer().allocate(kInstances, l);
  const RigParameters first = frame_values(1.0);
  const RigParameters second = frame_values(-0.5);
  const DeformedBatch<float> one = run(batch, first);
  // The first frame has no frame before it: no motion.
  EXPECT_EQ(one.previous_positions, one.positions);
  const DeformedBatch<float> two = run(batch, second);
  EXPECT_EQ(two.previous_positions, one.positions);
  EXPECT_NE(two.positions, one.positions);
  EXPECT_EQ(two.positions, planes_of(second).positions);
  EXPECT_EQ(batch.frames_written, 2u);
}

TEST(Handoff, HostMemoryIsWrittenInPlaceOnCpuDevices) {
  const RigParameters values = frame_values(0.9);
  const DeformedBatch<float> want = planes_of(values);
  const std::size_t vertices = deformer().output_vertices(VertexOrder::kMesh);
  OutputLayout l;
  l.order = VertexOrder::kMesh;
  l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, 16, 0);
  l.normals = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, vertices, 16, 12);
  const std::size_t bytes = OutputLayout::required_bytes(l.positions, kInstances, vertices);
  const std::size_t rounded = (bytes + 63) / 64 * 64;
  std::unique_ptr<void, decltype(&std::free)> memory(std::aligned_alloc(64, rounded), &std::free);
  std::memset(memory.get(), 0, rounded);
  HostOutputs host;
  host.positions = host.normals = memory.get();
  host.positions_bytes = host.normals_bytes = rounded;
  DeviceBatch batch = deformer().bind_host(kInstances, l, host);
  EXPECT_EQ(batch.positions(), batch.normals());  // one buffer for the interleaved vertex
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = NormalMode::kJacobian;
  job.outputs = &batch;
  deformer().enqueue(job);
  deformer().map_host(batch);
  EXPECT_TRUE(batch.host_mapped);
  const auto* floats = static_cast<const unsigned char*>(memory.get());
  for (std::size_t i = 0; i < kInstances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      glm::vec3 p;
      std::memcpy(&p, floats + (i * vertices + v) * 16, 12);
      ASSERT_EQ(p, want.position(i, v)) << "instance " << i << " vertex " << v;
    }
  }
  // The next frame unmaps by itself; read() decodes the same memory.
  deformer().enqueue(job);
  EXPECT_FALSE(batch.host_mapped);
  expect_matches(deformer().read(batch), want, l, "host memory");
}

TEST(Handoff, BadBindingsAreNamedAndNothingIsWritten) {
  const std::size_t slots = deformer().output_vertices(VertexOrder::kSlots);
  const OutputLayout l = interleaved_layout(slots);
  const std::size_t bytes = interleaved_bytes(l, slots);
  auto field_of = [](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& e) {
      return e.field();
    }
    return "accepted";
  };
  cl::Buffer small = device_buffer(bytes - 1);
  // One byte short: the tangents of the last vertex (the end of the vertex) do not fit.
  EXPECT_EQ(field_of([&] {
              deformer().bind(kInstances, l, {small, small, small, {}});
            }),
            "outputs.tangents");
  cl::Buffer enough = device_buffer(bytes);
  EXPECT_EQ(field_of([&] {
              deformer().bind(kInstances, l, {enough, enough, {}, {}});
            }),
            "outputs.tangents");  // no buffer for them
  OutputLayout misaligned = l;
  misaligned.normals.offset = 13;
  EXPECT_EQ(field_of([&] {
              deformer().bind(kInstances, misaligned, {enough, enough, enough, {}});
            }),
            "outputs.normals.offset");
  // Tangents from a mesh without them.
  const Mesh plain = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  ASSERT_FALSE(plain.has_tangents());
  const RiggedMesh blub = RiggedMesh::single_bend(plain, find_body_frame(plain), BendMode::kExact);
  ClDeformer blub_deformer(test::shared_context(), blub);
  OutputLayout with_tangents = blub_deformer.layout(1);
  with_tangents.tangents = with_tangents.normals;
  EXPECT_EQ(field_of([&] { blub_deformer.allocate(1, with_tangents); }), "outputs.tangents");
  // Host memory: the same pointer with two sizes.
  std::vector<float> memory(bytes / 4 + 1);
  HostOutputs host;
  host.positions = host.normals = host.tangents = memory.data();
  host.positions_bytes = host.tangents_bytes = bytes;
  host.normals_bytes = bytes + 4;
  EXPECT_EQ(field_of([&] { deformer().bind_host(kInstances, l, host); }), "outputs.normals_bytes");
  // Host memory that is not aligned to a float (vertices 2 bytes past a multiple of 4):
  // refused, whatever the format, as the kernels take every output buffer as floats.
  // FinFlex's planes with half normals: 4 bytes past a vector boundary are accepted,
  // 2 are not, for the positions or the halves.
  HostOutputs shifted = host;
  shifted.normals_bytes = bytes;
  shifted.positions = shifted.normals = shifted.tangents =
      reinterpret_cast<unsigned char*>(memory.data()) + 2;
  shifted.positions_bytes = shifted.normals_bytes = shifted.tangents_bytes = bytes - 2;
  EXPECT_EQ(field_of([&] { deformer().bind_host(kInstances, l, shifted); }), "outputs.positions");
  const OutputLayout half_planes = deformer().layout(kInstances, NormalFormat::kHalf);
  const std::size_t plane_floats =
      kInstances * 3 * deformer().layout(kInstances).positions.plane_stride;
  std::vector<float> positions(plane_floats + 1), directions(plane_floats + 1);
  HostOutputs planes;
  planes.positions = positions.data();
  planes.positions_bytes = plane_floats * 4;
  planes.normals = reinterpret_cast<unsigned char*>(directions.data()) + 4;
  planes.tangents = reinterpret_cast<unsigned char*>(directions.data()) + 4 + 2 * plane_floats;
  planes.normals_bytes = planes.tangents_bytes = 2 * plane_floats;
  EXPECT_EQ(field_of([&] { deformer().bind_host(kInstances, half_planes, planes); }), "accepted");
  planes.positions = reinterpret_cast<unsigned char*>(positions.data()) + 2;
  EXPECT_EQ(field_of([&] { deformer().bind_host(kInstances, half_planes, planes); }),
            "outputs.positions");
  planes.positions = positions.data();
  planes.tangents = reinterpret_cast<unsigned char*>(directions.data()) + 2 + 2 * plane_floats;
  EXPECT_EQ(field_of([&] { deformer().bind_host(kInstances, half_planes, planes); }),
            "outputs.tangents");
  // A batch changed by hand after binding is checked again: its buffer is now too small
  // for the layout, and nothing is written.
  DeviceBatch batch = deformer().bind(kInstances, l, {enough, enough, enough, {}});
  batch.outputs.positions.instance_stride *= 2;
  batch.outputs.normals.instance_stride *= 2;
  batch.outputs.tangents->instance_stride *= 2;
  const RigParameters values = frame_values(1.0);
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.outputs = &batch;
  EXPECT_EQ(field_of([&] { deformer().enqueue(job); }), "job.outputs.positions");
  const std::vector<unsigned char> untouched = raw(enough);
  for (unsigned char b : untouched) ASSERT_EQ(b, 0xAB);
}

}  // namespace
}  // namespace finflex

// The external-memory hand-off (finflex/external_outputs.hpp, the renderer's
// import_buffer): Vulkan devices matched by UUID, a fresh fd per export, every output
// layout written into exported memory exactly as into the engine's own buffers, and
// bad input named. On a CPU machine this runs on Mesa's lavapipe beside PoCL (memory
// written through the host mapping, imported by llvmpipe); on a GPU with
// cl_khr_external_memory_opaque_fd, imported by OpenCL. Without a Vulkan CPU device or
// loader the tests say so and skip.
#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#include "finflex/external_outputs.hpp"
#include "finflex/finflex.hpp"
#include "render/error.hpp"
#include "render/renderer.hpp"
#include "support/test_support.hpp"
#include "support/throws_error.hpp"

namespace finflex {
namespace {

constexpr std::size_t kInstances = 3;

// The Vulkan device for the tests' OpenCL device, or why there is none.
ExternalChoice& choice() {
  static ExternalChoice c = choose_external_device(test::shared_context());
  return c;
}

// Skips without external memory, unless FINFLEX_EXPECT_EXTERNAL_MEMORY says it must
// run here (CI: lavapipe is installed).
#define REQUIRE_EXTERNAL_MEMORY()                                                             \
  if (!choice().device) {                                                                     \
    if (std::getenv("FINFLEX_EXPECT_EXTERNAL_MEMORY") != nullptr) FAIL() << choice().why_not; \
    GTEST_SKIP() << "no external memory here: " << choice().why_not;                          \
  }

const RiggedMesh& barramundi() {
  static const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  static const RiggedMesh model(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh));
  return model;
}

bool is_open(int fd) { return fcntl(fd, F_GETFD) != -1; }

TEST(VulkanDevice, IsMatchedByUuidAndAMissingOneIsNamed) {
  REQUIRE_EXTERNAL_MEMORY();
  const vulkan::Device& device = *choice().device;
  std::printf("Vulkan: %s (%s), %s, semaphores %s; import %s\n", device.name().c_str(),
              vulkan::to_string(device.uuid()).c_str(), device.is_cpu() ? "CPU" : "GPU",
              device.exports_semaphores() ? "exported" : "not exported",
              to_string(choice().import));
  EXPECT_EQ(vulkan::Device::open(device.uuid())->name(), device.name());
  vulkan::Uuid missing{};
  missing.fill(0xEE);
  EXPECT_TRUE(test::ThrowsError([&] { vulkan::Device::open(missing); }, ErrorCode::kDevice,
                                "vulkan", {"no device with UUID eeeeeeee-eeee", device.name()}));
}

TEST(ExternalBuffer, EveryExportIsAFreshFdOfTheCallers) {
  REQUIRE_EXTERNAL_MEMORY();
  const vulkan::ExternalBuffer buffer(*choice().device, 1000);
  EXPECT_GE(buffer.memory_bytes(), buffer.bytes());
  const int first = buffer.export_fd();
  const int second = buffer.export_fd();
  EXPECT_NE(first, second);
  EXPECT_TRUE(is_open(first) && is_open(second));
  close(first);
  close(second);
  EXPECT_TRUE(test::ThrowsError([&] { vulkan::ExternalBuffer(*choice().device, 0); },
                                ErrorCode::kInvalidArgument, "bytes"));
}

// The bytes of each of a batch's buffers (positions, normals, tangents, previous
// positions; those its layout writes), read by OpenCL.
std::vector<std::vector<unsigned char>> buffer_bytes(Context& context, const DeviceBatch& batch) {
  std::vector<std::vector<unsigned char>> out;
  const cl::Buffer* buffers[4] = {&batch.positions, &batch.normals, &batch.tangents,
                                  &batch.previous_positions};
  const std::array<const AttributeLayout*, 4> written = batch.outputs.written();
  for (std::size_t k = 0; k < 4; ++k) {
    const cl::Buffer* b = buffers[k];
    if (written[k] == nullptr) continue;
    std::size_t bytes = 0;
    b->getInfo(CL_MEM_SIZE, &bytes);
    out.emplace_back(bytes);
    check_cl(context.queue().enqueueReadBuffer(*b, CL_TRUE, 0, bytes, out.back().data()),
             "clEnqueueReadBuffer");
  }
  return out;
}

struct Case {
  const char* name;
  OutputLayout layout;
  std::array<std::size_t, 4> buffer_of;
};

std::vector<Case> layouts(const ClDeformer& deformer) {
  std::vector<Case> out;
  OutputLayout planes = deformer.layout(kInstances);
  out.push_back({"planes", planes, {0, 1, 2, 3}});
  OutputLayout half = deformer.layout(kInstances, NormalFormat::kHalf);
  half.previous_positions = half.positions;
  out.push_back({"half normals, previous positions", half, {0, 1, 2, 3}});
  // One interleaved 32-byte vertex in mesh order: position, octahedral normal, a gap
  // of the caller's, snorm16 tangent.
  const std::size_t vertices = deformer.output_vertices(VertexOrder::kMesh);
  OutputLayout interleaved;
  interleaved.order = VertexOrder::kMesh;
  interleaved.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, 32, 0);
  interleaved.normals = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, vertices, 32, 12);
  interleaved.tangents = AttributeLayout::packed(AttributeFormat::kSnorm16x4, vertices, 32, 24);
  out.push_back({"interleaved", interleaved, {0, 0, 0, 0}});
  return out;
}

// Zeros in buffer b of `external`: through the mapping, or by OpenCL while acquired.
void zero(Context& context, ExternalOutputs& external, std::size_t b) {
  const vulkan::ExternalBuffer& buffer = external.buffer(b);
  if (external.import() == ExternalImport::kHostMapped) {
    std::memset(buffer.mapped(), 0, buffer.bytes());
    return;
  }
  const cl::Buffer* attributes[4] = {&external.batch().positions, &external.batch().normals,
                                     &external.batch().tangents,
                                     &external.batch().previous_positions};
  for (std::size_t k = 0; k < 4; ++k) {
    if (external.layout().written()[k] == nullptr || external.buffer_of(k) != b) continue;
    external.begin_reading();
    check_cl(
        context.queue().enqueueFillBuffer(*attributes[k], cl_uchar(0), 0, external.data_bytes(b)),
        "clEnqueueFillBuffer");
    external.end_reading();
    return;
  }
}

TEST(ExternalOutputs, EveryLayoutHoldsWhatTheEnginesOwnBuffersHold) {
  REQUIRE_EXTERNAL_MEMORY();
  Context& context = test::shared_context();
  ClDeformer deformer(context, barramundi());
  RigParameters values(barramundi(), kInstances);
  for (std::size_t i = 0; i < kInstances; ++i) {
    values.set(i, "body_m", 0.05f * float(i + 1));
    values.set(i, "tail_angle", 0.1f * float(i));
  }
  for (const Case& c : layouts(deformer)) {
    SCOPED_TRACE(c.name);
    ExternalOutputs external(deformer, kInstances, c.layout, *choice().device, c.buffer_of);
    EXPECT_EQ(external.import(), choice().import);
    // The engine's own buffers of the same sizes; both start as zeros (bytes the
    // layout does not write stay so).
    OutputBuffers own;
    cl::Buffer* slots[4] = {&own.positions, &own.normals, &own.tangents, &own.previous_positions};
    std::vector<cl::Buffer> made;
    for (std::size_t b = 0; b < external.buffer_count(); ++b) {
      made.emplace_back(context.context(), CL_MEM_READ_WRITE, external.data_bytes(b));
      check_cl(
          context.queue().enqueueFillBuffer(made.back(), cl_uchar(0), 0, external.data_bytes(b)),
          "clEnqueueFillBuffer");
    }
    const std::array<const AttributeLayout*, 4> written = c.layout.written();
    for (std::size_t k = 0; k < 4; ++k) {
      if (written[k]) *slots[k] = made[external.buffer_of(k)];
    }
    DeviceBatch reference = deformer.bind(kInstances, c.layout, own);
    // The exported memory starts as zeros too (its first contents are undefined).
    for (std::size_t b = 0; b < external.buffer_count(); ++b) zero(context, external, b);

    for (int frame = 0; frame < 2; ++frame) {
      ClJob job;
      job.instances = kInstances;
      job.parameters = values.view();
      job.outputs = &external.batch();
      external.enqueue(job);
      job.outputs = &reference;
      deformer.enqueue(job);
      external.begin_reading();
      const auto got = buffer_bytes(context, external.batch());
      external.end_reading();
      const auto expected = buffer_bytes(context, reference);
      ASSERT_EQ(got.size(), expected.size());
      for (std::size_t b = 0; b < got.size(); ++b) {
        EXPECT_TRUE(got[b] == expected[b]) << "buffer " << b << ", frame " << frame;
      }
      // On a CPU device the kernels wrote Vulkan's memory itself.
      if (external.import() == ExternalImport::kHostMapped) {
        external.wait_for_frame();
        const vulkan::ExternalBuffer& first = external.buffer(0);
        EXPECT_EQ(std::memcmp(first.mapped(), expected[0].data(), external.data_bytes(0)), 0);
      }
    }
  }
}

TEST(ExternalOutputs, AJobForAnotherBatchIsRefused) {
  REQUIRE_EXTERNAL_MEMORY();
  ClDeformer deformer(test::shared_context(), barramundi());
  ExternalOutputs external(deformer, kInstances, deformer.layout(kInstances), *choice().device);
  DeviceBatch other = deformer.allocate(kInstances);
  RigParameters values(barramundi(), kInstances);
  ClJob job;
  job.instances = kInstances;
  job.parameters = values.view();
  job.outputs = &other;
  EXPECT_TRUE(test::ThrowsError([&] { external.enqueue(job); }, ErrorCode::kInvalidArgument,
                                "job.outputs"));
}

// The side region: each frame's copies land where they are asked, after the data and
// aligned; a copy past it or without a source is refused, naming it.
TEST(ExternalOutputs, SideCopiesLandBesideTheOutputs) {
  REQUIRE_EXTERNAL_MEMORY();
  Context& context = test::shared_context();
  ClDeformer deformer(context, barramundi());
  ExternalOutputs external(deformer, kInstances, deformer.layout(kInstances), *choice().device,
                           {0, 1, 2, 3}, 256, 64);
  EXPECT_EQ(external.side_bytes(), 64u);
  EXPECT_GE(external.side_offset(), external.data_bytes(0));
  EXPECT_EQ(external.side_offset() % 256, 0u);
  std::vector<cl_uint> words(16);
  for (std::size_t i = 0; i < words.size(); ++i) words[i] = cl_uint(100 + i);
  cl::Buffer source(context.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                    words.size() * sizeof(cl_uint), words.data());
  RigParameters values(barramundi(), kInstances);
  ClJob job;
  job.instances = kInstances;
  job.parameters = values.view();
  job.outputs = &external.batch();
  const std::vector<SideCopy> bad{{&source, 0, 8, 0}, {&source, 0, 8, 60}};
  EXPECT_TRUE(test::ThrowsError([&] { external.enqueue(job, nullptr, bad); },
                                ErrorCode::kInvalidArgument, "copies[1]"));
  EXPECT_TRUE(test::ThrowsError(
      [&] {
        external.enqueue(job, nullptr, {{nullptr, 0, 4, 0}});
      },
      ErrorCode::kInvalidArgument, "copies[0]"));
  // Words 2..7 to bytes 4..28, words 0..1 to bytes 40..48.
  external.enqueue(job, nullptr, {{&source, 8, 24, 4}, {&source, 0, 8, 40}});
  external.wait_for_frame();
  if (external.import() != ExternalImport::kHostMapped) GTEST_SKIP() << "the GPU's memory";
  const auto* side = reinterpret_cast<const cl_uint*>(
      static_cast<const unsigned char*>(external.buffer(0).mapped()) + external.side_offset());
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(side[1 + i], 102 + i);
  EXPECT_EQ(side[10], 100u);
  EXPECT_EQ(side[11], 101u);
}

// The renderer's import: bad fds and sizes named, nothing imported.
render::ErrorCode import_error(render::Renderer& renderer, int fd, std::size_t memory_bytes,
                               std::size_t bytes, std::string& field) {
  try {
    renderer.import_buffer(fd, memory_bytes, bytes);
  } catch (const render::RenderError& e) {
    field = e.field();
    return e.code();
  }
  ADD_FAILURE() << "import_buffer(" << fd << ", " << memory_bytes << ", " << bytes
                << ") was accepted";
  return render::ErrorCode::kIo;
}

TEST(RendererImport, BadFdsAndSizesAreNamed) {
  render::Renderer renderer({64, 64, 1});
  std::string field;
  if (!renderer.external_support().memory) {
    std::printf("GL imports no memory: %s\n", renderer.external_support().why_not.c_str());
    EXPECT_EQ(import_error(renderer, -1, 4096, 1024, field), render::ErrorCode::kGraphics);
    return;
  }
  EXPECT_EQ(import_error(renderer, -1, 4096, 1024, field), render::ErrorCode::kInvalidArgument);
  EXPECT_EQ(field, "fd");
  REQUIRE_EXTERNAL_MEMORY();
  const vulkan::ExternalBuffer buffer(*choice().device, 4096);
  EXPECT_EQ(import_error(renderer, buffer.export_fd(), buffer.memory_bytes(), 0, field),
            render::ErrorCode::kInvalidArgument);
  EXPECT_EQ(field, "bytes");
  EXPECT_EQ(import_error(renderer, buffer.export_fd(), buffer.memory_bytes(),
                         buffer.memory_bytes() + 1, field),
            render::ErrorCode::kInvalidArgument);
  EXPECT_EQ(field, "bytes");
  // A lost fd: closed before the import.
  const int lost = buffer.export_fd();
  close(lost);
  EXPECT_EQ(import_error(renderer, lost, buffer.memory_bytes(), 1024, field),
            render::ErrorCode::kGraphics);
  // And a good one imports.
  const render::BufferId imported =
      renderer.import_buffer(buffer.export_fd(), buffer.memory_bytes(), 4096 - 64);
  EXPECT_EQ(renderer.buffer_bytes(imported), 4096u - 64u);
  if (!renderer.external_support().semaphores) {
    EXPECT_THROW(renderer.import_semaphore(-1), render::RenderError);
  }
}

}  // namespace
}  // namespace finflex

// Outputs into OpenGL buffers (finflex/gl_outputs.hpp) on the renderer's EGL context:
// the path taken and why, the GL buffer holding what the kernels wrote (an interleaved
// vertex with a byte range of the caller's that FinFlex must leave alone), and bad
// GL buffers named. On PoCL and Mesa this is the copy path; on a GPU whose OpenCL
// shares EGL contexts, the shared one.
#include <cstring>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "finflex/gl_outputs.hpp"
#include "render/renderer.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

constexpr std::size_t kInstances = 2;
constexpr std::size_t kStride =
    32;  // position 0-11, normal 12-15, the caller's 16-23, tangent 24-31

OutputLayout vertex_layout(std::size_t vertices) {
  OutputLayout l;
  l.order = VertexOrder::kMesh;
  l.positions = AttributeLayout::packed(AttributeFormat::kFloat32x3, vertices, kStride, 0);
  l.normals = AttributeLayout::packed(AttributeFormat::kOctahedral16x2, vertices, kStride, 12);
  l.tangents = AttributeLayout::packed(AttributeFormat::kSnorm16x4, vertices, kStride, 24);
  return l;
}

std::vector<unsigned char> gl_contents(std::uint32_t name, std::size_t bytes) {
  std::vector<unsigned char> out(bytes);
  glBindBuffer(GL_ARRAY_BUFFER, name);
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

TEST(GlOutputs, TheGlBufferHoldsTheFrameAndTheCallersBytes) {
  render::Renderer renderer({64, 64, 1});
  GlSharingContext gl = make_gl_sharing_context(test::shared_context().description().device_name,
                                                renderer.egl_display(), renderer.egl_context());
  ASSERT_TRUE(gl.context);
  if (!gl.sharing) {
    EXPECT_FALSE(gl.why_not.empty());
    std::printf("GL sharing: none (%s)\n", gl.why_not.c_str());
  }
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh model(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh));
  ClDeformer deformer(*gl.context, model);
  const std::size_t vertices = mesh.vertex_count();
  const std::size_t bytes = kInstances * vertices * kStride;
  // The caller's vertex buffer: every byte 0x5A, so the caller's range is recognisable.
  const render::BufferId buffer = renderer.create_buffer(bytes);
  renderer.write_buffer(buffer, 0, std::vector<unsigned char>(bytes, 0x5A).data(), bytes);
  const std::uint32_t name = renderer.gl_buffer(buffer);
  GlOutputs outputs(deformer, kInstances, vertex_layout(vertices), {name, name, name, 0});
  EXPECT_EQ(outputs.path(), gl.sharing ? GlPath::kShared : GlPath::kCopy);
  std::printf("GL hand-off path: %s\n", to_string(outputs.path()));

  const RigParameters values = test::at_fractions_of_the_limits(model, {0.8, -0.6});
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = NormalMode::kJacobian;
  job.outputs = &outputs.batch();
  cl::Event ready = outputs.enqueue(job);
  check_cl(ready.wait(), "clWaitForEvents");

  // What the kernels write in FinFlex's planes, for comparison.
  DeviceBatch planes = deformer.allocate(kInstances);
  job.outputs = &planes;
  deformer.enqueue(job);
  const DeformedBatch<float> want = deformer.read(planes);

  renderer.make_current();
  const std::vector<unsigned char> got = gl_contents(name, bytes);
  for (std::size_t i = 0; i < kInstances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      const unsigned char* vertex = got.data() + (i * vertices + v) * kStride;
      glm::vec3 p;
      std::memcpy(&p, vertex, 12);
      ASSERT_EQ(p, want.position(i, v)) << "instance " << i << " vertex " << v;
      for (std::size_t k = 16; k < 24; ++k) ASSERT_EQ(vertex[k], 0x5A) << "caller's byte " << k;
      std::int16_t w = 0;
      std::memcpy(&w, vertex + 30, 2);
      ASSERT_EQ(w, mesh.tangents[v].w < 0 ? -32767 : 32767);
    }
  }
  EXPECT_GE(outputs.last_handoff_seconds(), 0.0);
}

TEST(GlOutputs, BadGlBuffersAreNamed) {
  render::Renderer renderer({16, 16, 1});
  GlSharingContext gl = make_gl_sharing_context(test::shared_context().description().device_name,
                                                renderer.egl_display(), renderer.egl_context());
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  ClDeformer deformer(*gl.context, model);
  const std::size_t vertices = mesh.vertex_count();
  auto field_of = [&](const GlBuffers& buffers) -> std::string {
    try {
      GlOutputs outputs(deformer, kInstances, vertex_layout(vertices), buffers);
    } catch (const Error& e) {
      return e.field();
    }
    return "accepted";
  };
  const std::uint32_t small =
      renderer.gl_buffer(renderer.create_buffer(kInstances * vertices * kStride - 1));
  renderer.make_current();
  EXPECT_EQ(field_of({small, small, small, 0}), "outputs.tangents");  // the last bytes
  EXPECT_EQ(field_of({small, 0, small, 0}), "outputs.normals");       // none given
  EXPECT_EQ(field_of({9999, 9999, 9999, 0}), "outputs.positions");    // no such buffer
}

}  // namespace
}  // namespace finflex

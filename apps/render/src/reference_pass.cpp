#include "reference_pass.hpp"

#include <climits>
#include <string>

#include "render/error.hpp"

namespace finflex::render::detail {

ReferencePass::ReferencePass()
    : program_("reference", {"scene_block.glsl", "reference.vert.glsl"}, {"reference.frag.glsl"}),
      vertex_array_(GlVertexArray::create()) {
  program_.bind_block("Scene", 0);
}

void ReferencePass::validate(const std::vector<FishDraw>& fish) {
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& f = fish[d];
    if (f.instance_count == 0) continue;
    const StreamLayout& layout = f.positions.layout;
    if (f.list.buffer != kNoBuffer) {
      throw RenderError(ErrorCode::kInvalidArgument, "fish[" + std::to_string(d) + "].list",
                        "fish[" + std::to_string(d) +
                            "].list: the reference draw counts its instances on the host");
    }
    const std::string field = "fish[" + std::to_string(d) + "].positions";
    if (f.positions.buffer == kNoBuffer || layout.type != ComponentType::kFloat32 ||
        layout.vertex_stride == 0 || layout.instance_stride % layout.vertex_stride != 0 ||
        (f.instance_count - 1) * (layout.instance_stride / layout.vertex_stride) >
            static_cast<std::size_t>(INT_MAX)) {
      throw RenderError(ErrorCode::kInvalidArgument, field,
                        field +
                            ": the reference draw reads float32 positions in a renderer "
                            "buffer whose instance stride is a multiple of its vertex stride");
    }
  }
}

void ReferencePass::draw(const std::vector<FishDraw>& fish,
                         const std::vector<MeshResources>& meshes,
                         const std::vector<BufferResource>& buffers) {
  program_.use();
  glBindVertexArray(vertex_array_.get());
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& f = fish[d];
    if (f.instance_count == 0) continue;
    const StreamLayout& layout = f.positions.layout;
    const MeshResources& mesh = meshes[f.mesh];
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffers[f.positions.buffer].buffer.get());
    for (GLuint c = 0; c < 3; ++c) {
      glEnableVertexAttribArray(c);
      glVertexAttribPointer(
          c, 1, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(layout.vertex_stride),
          reinterpret_cast<const void*>(layout.offset + c * layout.component_stride));
    }
    counts_.assign(f.instance_count, mesh.index_count);
    firsts_.assign(f.instance_count, nullptr);
    base_vertices_.resize(f.instance_count);
    const std::size_t step = layout.instance_stride / layout.vertex_stride;
    for (std::size_t i = 0; i < f.instance_count; ++i) {
      base_vertices_[i] = static_cast<GLint>(i * step);
    }
    glMultiDrawElementsBaseVertex(GL_TRIANGLES, counts_.data(), GL_UNSIGNED_INT, firsts_.data(),
                                  static_cast<GLsizei>(f.instance_count), base_vertices_.data());
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(0);
}

}  // namespace finflex::render::detail

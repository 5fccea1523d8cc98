#include "encode_pass.hpp"

namespace finflex::render::detail {

EncodePass::EncodePass()
    : program_("encode", {"fullscreen.vert.glsl"}, {"encode.frag.glsl"}),
      vertex_array_(GlVertexArray::create()) {
  program_.bind_sampler("u_linear", 0);
}

void EncodePass::draw(const RenderTargets& targets) {
  targets.bind_output();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);
  program_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, targets.resolved_texture());
  glBindVertexArray(vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace finflex::render::detail

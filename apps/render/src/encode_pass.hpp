// The output transform: the resolved linear frame to sRGB-encoded RGBA8, flipped so
// that glReadPixels returns rows from the top (shaders/encode.frag.glsl).
#pragma once

#include "gl_object.hpp"
#include "render_targets.hpp"
#include "shader_program.hpp"

namespace finflex::render::detail {

class EncodePass {
 public:
  EncodePass();
  void draw(const RenderTargets& targets);

 private:
  ShaderProgram program_;
  GlVertexArray vertex_array_;  // empty: the triangle comes from gl_VertexID
};

}  // namespace finflex::render::detail

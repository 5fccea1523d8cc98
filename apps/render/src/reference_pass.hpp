// The reference draw: the same triangles as the fish pass, drawn the cheapest way, so
// that the fish pass's GPU time has a yardstick in the same run (docs/rendering.md
// "The reference draw"). Every FishDraw's positions are read as plain vertex
// attributes straight from its buffer (x, y and z one float attribute each, at the
// stream's component offsets), every instance one command of a single
// glMultiDrawElementsBaseVertex per species (an instance's vertices start
// instance_stride / vertex_stride vertices on), a pass-through vertex shader, one flat
// colour, into the colour pass's multisampled framebuffer. Transforms and normals are
// not read.
#pragma once

#include <vector>

#include "gl_resources.hpp"
#include "render/fish_draw.hpp"
#include "shader_program.hpp"

namespace finflex::render::detail {

class ReferencePass {
 public:
  ReferencePass();
  // After validate_fish(), before any GL call: each draw's positions must be a
  // renderer buffer of float32 whose instance stride is a multiple of its vertex
  // stride (FinFlex's planes and interleaved xyz are), with no device list:
  // kInvalidArgument naming "fish[d].positions" or "fish[d].list" otherwise.
  static void validate(const std::vector<FishDraw>& fish);
  // `fish` passed validate(). Needs the scene framebuffer bound and the Scene block
  // at binding 0.
  void draw(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
            const std::vector<BufferResource>& buffers);

 private:
  ShaderProgram program_;
  GlVertexArray vertex_array_;
  std::vector<GLsizei> counts_;
  std::vector<const void*> firsts_;
  std::vector<GLint> base_vertices_;
};

}  // namespace finflex::render::detail

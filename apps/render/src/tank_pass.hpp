// Draws the tanks (tank_mesh.hpp; one instance per tank of the rows) with ordinary
// vertex attributes; the mesh is rebuilt only when the tank's shape or colours change.
#pragma once

#include <optional>

#include "gl_object.hpp"
#include "render/scene.hpp"
#include "shader_program.hpp"

namespace finflex::render::detail {

class TankPass {
 public:
  explicit TankPass(bool refraction = false);  // as FishPass's refraction
  // Needs the scene framebuffer bound and the Scene block at binding 0.
  void draw(const Tank& tank, const TankRows& rows);

 private:
  ShaderProgram program_;
  GlVertexArray vertex_array_;
  GlBuffer vertices_;
  GlBuffer indices_;
  GLsizei index_count_ = 0;
  std::optional<Tank> built_for_;

  void rebuild(const Tank& tank);
};

}  // namespace finflex::render::detail

// The id pass's framebuffer: one sample per pixel, an unsigned integer colour target
// (GL_R32UI: a fish instance's id, 0 for none) and a 32-bit float depth target, read
// back as they are (no resolve, no encoding).
#pragma once

#include "gl_object.hpp"
#include "render/id_image.hpp"

namespace finflex::render::detail {

class IdTargets {
 public:
  // Throws RenderError (kGraphics) when the framebuffer is incomplete.
  IdTargets(int width, int height);

  // Draw framebuffer and viewport; clears ids to 0 and depth to 1.
  void bind_and_clear() const;
  // The ids and the depth buffer's values (0..1, rows from the top), the depth turned
  // into distances along the view axis for a perspective projection with these planes.
  void read(IdImage& out, float near_plane, float far_plane) const;

 private:
  int width_;
  int height_;
  GlRenderbuffer ids_;
  GlRenderbuffer depth_;
  GlFramebuffer framebuffer_;
};

}  // namespace finflex::render::detail

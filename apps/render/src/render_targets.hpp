// The framebuffers of a frame, in the order a frame passes through them:
//   scene:    multisampled RGBA16F colour (linear light) + 24-bit depth;
//   resolved: one sample, RGBA16F texture (glBlitFramebuffer averages the samples in
//             linear light, which is what antialiasing should average);
//   output:   RGBA8, sRGB-encoded by the encode pass, read back by glReadPixels.
#pragma once

#include "gl_object.hpp"

namespace finflex::render::detail {

// A renderbuffer of `format`, multisampled when samples > 1.
GlRenderbuffer renderbuffer(GLenum format, int width, int height, int samples);
// Throws RenderError (kGraphics) naming the framebuffer bound to GL_FRAMEBUFFER when it
// is incomplete.
void require_complete(const char* name);

class RenderTargets {
 public:
  // `samples` >= 1, within the driver's GL_MAX_SAMPLES. Throws RenderError (kGraphics)
  // when a framebuffer is incomplete.
  RenderTargets(int width, int height, int samples);

  void bind_scene() const;   // draw framebuffer and viewport for the scene passes
  void resolve() const;      // scene -> resolved
  void bind_output() const;  // draw framebuffer and viewport for the encode pass
  void bind_output_for_reading() const;
  GLuint resolved_texture() const { return resolved_colour_.get(); }

 private:
  int width_;
  int height_;
  GlRenderbuffer scene_colour_;
  GlRenderbuffer scene_depth_;
  GlFramebuffer scene_;
  GlTexture resolved_colour_;
  GlFramebuffer resolved_;
  GlRenderbuffer output_colour_;
  GlFramebuffer output_;
};

}  // namespace finflex::render::detail

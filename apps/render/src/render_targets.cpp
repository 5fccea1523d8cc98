#include "render_targets.hpp"

#include <cstdio>
#include <string>

#include "render/error.hpp"

namespace finflex::render::detail {

GlRenderbuffer renderbuffer(GLenum format, int width, int height, int samples) {
  GlRenderbuffer buffer = GlRenderbuffer::create();
  glBindRenderbuffer(GL_RENDERBUFFER, buffer.get());
  if (samples > 1) {
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  } else {
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  return buffer;
}

void require_complete(const char* name) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", status);
    throw RenderError(
        ErrorCode::kGraphics, name,
        std::string("the ") + name + " framebuffer is incomplete (status " + code + ")");
  }
}

RenderTargets::RenderTargets(int width, int height, int samples) : width_(width), height_(height) {
  scene_colour_ = renderbuffer(GL_RGBA16F, width, height, samples);
  scene_depth_ = renderbuffer(GL_DEPTH_COMPONENT24, width, height, samples);
  scene_ = GlFramebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, scene_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            scene_colour_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            scene_depth_.get());
  require_complete("multisampled scene");

  resolved_colour_ = GlTexture::create();
  glBindTexture(GL_TEXTURE_2D, resolved_colour_.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_HALF_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  resolved_ = GlFramebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, resolved_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                         resolved_colour_.get(), 0);
  require_complete("resolved");

  output_colour_ = renderbuffer(GL_RGBA8, width, height, 1);
  output_ = GlFramebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, output_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            output_colour_.get());
  require_complete("output");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void RenderTargets::bind_scene() const {
  glBindFramebuffer(GL_FRAMEBUFFER, scene_.get());
  glViewport(0, 0, width_, height_);
}

void RenderTargets::resolve() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, scene_.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_.get());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void RenderTargets::bind_output() const {
  glBindFramebuffer(GL_FRAMEBUFFER, output_.get());
  glViewport(0, 0, width_, height_);
}

void RenderTargets::bind_output_for_reading() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, output_.get());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
}

}  // namespace finflex::render::detail

#include "id_targets.hpp"

#include <cstddef>
#include <limits>
#include <vector>

#include "render/error.hpp"
#include "render_targets.hpp"

namespace finflex::render::detail {

IdTargets::IdTargets(int width, int height, std::size_t in_flight)
    : width_(width),
      height_(height),
      ids_(renderbuffer(GL_R32UI, width, height, 1)),
      depth_(renderbuffer(GL_DEPTH_COMPONENT32F, width, height, 1)),
      framebuffer_(GlFramebuffer::create()),
      ring_("take_ids", width, height,
            {{GL_COLOR_ATTACHMENT0, GL_RED_INTEGER, GL_UNSIGNED_INT, 4},
             {GL_NONE, GL_DEPTH_COMPONENT, GL_FLOAT, 4}},
            in_flight) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ids_.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.get());
  require_complete("id");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void IdTargets::bind_and_clear() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, width_, height_);
  const GLuint no_id[4] = {0, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, no_id);
  const GLfloat far_depth = 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &far_depth);
}

void IdTargets::request(float near_plane, float far_plane) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
  ring_.request();
  planes_.push_back({near_plane, far_plane});
}

void IdTargets::take(IdImage& out) {
  if (planes_.empty()) {
    throw RenderError(ErrorCode::kInvalidArgument, "take_ids", "take_ids: no id pass requested");
  }
  const Planes p = planes_.front();
  planes_.pop_front();
  ring_.take([&](const std::vector<const void*>& planes) {
    to_id_image(static_cast<const GLuint*>(planes[0]), static_cast<const GLfloat*>(planes[1]),
                p.near_plane, p.far_plane, out);
  });
}

void IdTargets::read(IdImage& out, float near_plane, float far_plane) const {
  const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  std::vector<GLuint> ids(pixels);
  std::vector<GLfloat> depth(pixels);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  to_id_image(ids.data(), depth.data(), near_plane, far_plane, out);
}

void IdTargets::to_id_image(const GLuint* ids, const GLfloat* depth, float near_plane,
                            float far_plane, IdImage& out) const {
  const auto width = static_cast<std::size_t>(width_);
  const auto height = static_cast<std::size_t>(height_);
  out.width = width_;
  out.height = height_;
  out.ids.resize(width * height);
  out.depth.resize(width * height);
  // Window depth d in [0, 1] of a perspective projection (gluPerspective, depth range
  // 0..1) at view distance z: d = (f (z - n)) / (z (f - n)), so z = n f / (f - d (f - n)).
  const float n = near_plane;
  const float f = far_plane;
  for (std::size_t y = 0; y < height; ++y) {
    const std::size_t from = (height - 1 - y) * width;  // GL rows start at the bottom
    for (std::size_t x = 0; x < width; ++x) {
      out.ids[y * width + x] = ids[from + x];
      const float d = depth[from + x];
      out.depth[y * width + x] =
          d >= 1.0f ? std::numeric_limits<float>::infinity() : n * f / (f - d * (f - n));
    }
  }
}

}  // namespace finflex::render::detail

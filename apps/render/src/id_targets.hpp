// The id pass's framebuffer: one sample per pixel, an unsigned integer colour target
// (GL_R32UI: a fish instance's id, 0 for none) and a 32-bit float depth target, read
// back as they are (no resolve, no encoding), through a ring of pixel-pack buffers
// (frames_in_flight.hpp) so that several id passes may be in flight.
#pragma once

#include <cstddef>
#include <deque>

#include "frames_in_flight.hpp"
#include "gl_object.hpp"
#include "render/id_image.hpp"

namespace finflex::render::detail {

class IdTargets {
 public:
  // Throws RenderError (kGraphics) when the framebuffer is incomplete. `in_flight`:
  // how many id passes may be read back at once.
  IdTargets(int width, int height, std::size_t in_flight);

  // Draw framebuffer and viewport; clears ids to 0 and depth to 1.
  void bind_and_clear() const;

  std::size_t in_flight() const { return ring_.depth(); }
  std::size_t pending() const { return ring_.pending(); }
  // Starts reading the last id pass back (the caller checks pending() < in_flight());
  // its depth turns into distances along the view axis for a perspective projection
  // with these planes.
  void request(float near_plane, float far_plane);
  // The oldest requested id pass: its ids and distances, rows from the top.
  void take(IdImage& out);
  // The last id pass, as take gives it, read at once (waits for the GPU).
  void read(IdImage& out, float near_plane, float far_plane) const;

 private:
  int width_;
  int height_;
  GlRenderbuffer ids_;
  GlRenderbuffer depth_;
  GlFramebuffer framebuffer_;
  ReadbackRing ring_;
  struct Planes {
    float near_plane;
    float far_plane;
  };
  std::deque<Planes> planes_;  // per pending pass
  void to_id_image(const GLuint* ids, const GLfloat* depth, float near_plane, float far_plane,
                   IdImage& out) const;
};

}  // namespace finflex::render::detail

// The renderer's frames in flight: frames (colour, ids) read back through a ring of
// pixel-pack buffers, each slot with a fence, so that the host takes a frame only when the
// GPU has drawn it and never waits for the frames drawn after it; and the GPU time of
// each frame's passes from a ring of timer queries, read once their results are there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include <epoxy/gl.h>

#include "gl_object.hpp"

namespace finflex::render::detail {

// One plane of a frame read back: glReadPixels of `format` and `type` from the bound
// read framebuffer, after glReadBuffer(source) unless source is GL_NONE (depth, or the
// read buffer already chosen); pixel_bytes per pixel, rows packed at alignment 1.
struct PixelPlane {
  GLenum source = GL_NONE;
  GLenum format = GL_RGB;
  GLenum type = GL_UNSIGNED_BYTE;
  std::size_t pixel_bytes = 3;
};

class ReadbackRing {
 public:
  // `what` names the frames in errors ("take_image", "take_ids").
  ReadbackRing(const char* what, int width, int height, std::vector<PixelPlane> planes,
               std::size_t depth);
  ~ReadbackRing();
  ReadbackRing(const ReadbackRing&) = delete;
  ReadbackRing& operator=(const ReadbackRing&) = delete;

  std::size_t depth() const { return slots_.size(); }
  std::size_t pending() const { return pending_.size(); }
  // Every plane of the bound read framebuffer into the next free slot, and a fence.
  // The caller checks pending() < depth().
  void request();
  // The oldest pending frame: waits for its fence only, then hands `read` each plane's
  // mapped pixels (rows as glReadPixels wrote them: from the bottom), in plane order.
  void take(const std::function<void(const std::vector<const void*>& planes)>& read);

 private:
  const char* what_;
  int width_;
  int height_;
  std::vector<PixelPlane> planes_;
  std::vector<std::vector<GlBuffer>> slots_;  // per slot, a buffer per plane
  std::size_t next_ = 0;
  struct Pending {
    std::size_t slot;
    GLsync fence;
  };
  std::deque<Pending> pending_;
  std::size_t plane_bytes(const PixelPlane& plane) const;
};

class GpuTimer {
 public:
  explicit GpuTimer(std::size_t depth);
  void begin();
  void end();
  // The GPU seconds of the latest timed frame whose result is available, without
  // waiting (0 before the first).
  double latest_seconds();

 private:
  std::vector<GlQuery> queries_;
  std::vector<bool> issued_;
  std::size_t next_ = 0;
  double latest_ = 0.0;
  // Each slot's query's serial (its frame): the first query's result (serial 0) is
  // dropped, since llvmpipe counts it from its clock's origin (thousands of seconds),
  // and latest_ only moves to a newer frame's.
  std::vector<std::uint64_t> serial_;
  std::uint64_t issued_count_ = 0;
  std::uint64_t latest_serial_ = 0;
  void take(std::size_t slot);
};

}  // namespace finflex::render::detail

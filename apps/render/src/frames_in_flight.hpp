// The renderer's frames in flight: colour frames read back through a ring of
// pixel-pack buffers, each with a fence, so that the host takes a frame only when the
// GPU has drawn it and never waits for the frames drawn after it; and the GPU time of
// each frame's passes from a ring of timer queries, read once their results are there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include <epoxy/gl.h>

#include "gl_object.hpp"
#include "render/image.hpp"

namespace finflex::render::detail {

class ReadbackRing {
 public:
  ReadbackRing(int width, int height, std::size_t depth);
  ~ReadbackRing();
  ReadbackRing(const ReadbackRing&) = delete;
  ReadbackRing& operator=(const ReadbackRing&) = delete;

  std::size_t depth() const { return buffers_.size(); }
  std::size_t pending() const { return pending_.size(); }
  // glReadPixels of the bound read framebuffer into the next free buffer, and a fence.
  // The caller checks pending() < depth().
  void request();
  // The oldest pending frame: waits for its fence, copies it out (rows from the top, as
  // the encode pass wrote them).
  void take(Image& out);

 private:
  int width_;
  int height_;
  std::vector<GlBuffer> buffers_;
  std::size_t next_ = 0;
  struct Pending {
    std::size_t buffer;
    GLsync fence;
  };
  std::deque<Pending> pending_;
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

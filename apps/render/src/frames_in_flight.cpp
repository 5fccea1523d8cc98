#include "frames_in_flight.hpp"

#include <string>
#include <utility>

#include "render/error.hpp"

namespace finflex::render::detail {

ReadbackRing::ReadbackRing(const char* what, int width, int height, std::vector<PixelPlane> planes,
                           std::size_t depth)
    : what_(what), width_(width), height_(height), planes_(std::move(planes)), slots_(depth) {
  for (std::vector<GlBuffer>& slot : slots_) {
    for (const PixelPlane& plane : planes_) {
      slot.push_back(GlBuffer::create());
      glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.back().get());
      glBufferData(GL_PIXEL_PACK_BUFFER, static_cast<GLsizeiptr>(plane_bytes(plane)), nullptr,
                   GL_STREAM_READ);
    }
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

ReadbackRing::~ReadbackRing() {
  for (const Pending& p : pending_) glDeleteSync(p.fence);
}

std::size_t ReadbackRing::plane_bytes(const PixelPlane& plane) const {
  return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * plane.pixel_bytes;
}

void ReadbackRing::request() {
  const std::size_t slot = next_;
  next_ = (next_ + 1) % slots_.size();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (std::size_t k = 0; k < planes_.size(); ++k) {
    const PixelPlane& plane = planes_[k];
    if (plane.source != GL_NONE) glReadBuffer(plane.source);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, slots_[slot][k].get());
    glReadPixels(0, 0, width_, height_, plane.format, plane.type, nullptr);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  pending_.push_back({slot, glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0)});
  glFlush();  // the reads go to the GPU now, so the fence can signal
}

void ReadbackRing::take(const std::function<void(const std::vector<const void*>& planes)>& read) {
  if (pending_.empty()) {
    throw RenderError(ErrorCode::kInvalidArgument, what_,
                      std::string(what_) + ": no frame requested");
  }
  const Pending p = pending_.front();
  pending_.pop_front();
  const GLenum waited = glClientWaitSync(p.fence, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(60e9));
  glDeleteSync(p.fence);
  if (waited == GL_TIMEOUT_EXPIRED || waited == GL_WAIT_FAILED) {
    throw RenderError(ErrorCode::kGraphics, "gl",
                      std::string(what_) + ": the frame's fence never signalled");
  }
  std::vector<const void*> mapped;
  for (std::size_t k = 0; k < planes_.size(); ++k) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, slots_[p.slot][k].get());
    mapped.push_back(glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0,
                                      static_cast<GLsizeiptr>(plane_bytes(planes_[k])),
                                      GL_MAP_READ_BIT));
  }
  const auto unmap = [&] {
    for (std::size_t k = 0; k < planes_.size(); ++k) {
      if (mapped[k] == nullptr) continue;
      glBindBuffer(GL_PIXEL_PACK_BUFFER, slots_[p.slot][k].get());
      glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  };
  for (const void* plane : mapped) {
    if (plane != nullptr) continue;
    unmap();
    throw RenderError(ErrorCode::kGraphics, "gl",
                      std::string(what_) + ": the pixel buffer could not be mapped");
  }
  try {
    read(mapped);
  } catch (...) {
    unmap();
    throw;
  }
  unmap();
}

GpuTimer::GpuTimer(std::size_t depth) : issued_(depth, false), serial_(depth, 0) {
  for (std::size_t k = 0; k < depth; ++k) queries_.push_back(GlQuery::create());
}

void GpuTimer::take(std::size_t slot) {
  GLuint64 ns = 0;
  glGetQueryObjectui64v(queries_[slot].get(), GL_QUERY_RESULT, &ns);
  if (serial_[slot] > latest_serial_) {
    latest_ = double(ns) * 1e-9;
    latest_serial_ = serial_[slot];
  }
  issued_[slot] = false;
}

void GpuTimer::begin() {
  // A query still waiting for its result is read (waiting) before it is reused: with
  // `depth` frames in flight that is a frame the GPU finished long ago.
  if (issued_[next_]) take(next_);
  glBeginQuery(GL_TIME_ELAPSED, queries_[next_].get());
}

void GpuTimer::end() {
  glEndQuery(GL_TIME_ELAPSED);
  issued_[next_] = true;
  serial_[next_] = issued_count_++;
  next_ = (next_ + 1) % queries_.size();
}

double GpuTimer::latest_seconds() {
  // The newest issued query with a result, looking back from the last one issued.
  for (std::size_t back = 1; back <= queries_.size(); ++back) {
    const std::size_t k = (next_ + queries_.size() - back) % queries_.size();
    if (!issued_[k]) continue;
    GLuint available = 0;
    glGetQueryObjectuiv(queries_[k].get(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) continue;
    take(k);
    break;
  }
  return latest_;
}

}  // namespace finflex::render::detail

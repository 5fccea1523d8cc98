#include "frames_in_flight.hpp"

#include <cstring>

#include "render/error.hpp"

namespace finflex::render::detail {

ReadbackRing::ReadbackRing(int width, int height, std::size_t depth)
    : width_(width), height_(height) {
  const auto bytes = static_cast<GLsizeiptr>(width) * height * 3;
  for (std::size_t k = 0; k < depth; ++k) {
    buffers_.push_back(GlBuffer::create());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffers_.back().get());
    glBufferData(GL_PIXEL_PACK_BUFFER, bytes, nullptr, GL_STREAM_READ);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

ReadbackRing::~ReadbackRing() {
  for (const Pending& p : pending_) glDeleteSync(p.fence);
}

void ReadbackRing::request() {
  const std::size_t buffer = next_;
  next_ = (next_ + 1) % buffers_.size();
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffers_[buffer].get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  pending_.push_back({buffer, glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0)});
  glFlush();  // the read goes to the GPU now, so its fence can signal
}

void ReadbackRing::take(Image& out) {
  if (pending_.empty()) {
    throw RenderError(ErrorCode::kInvalidArgument, "take_image", "take_image: no frame requested");
  }
  const Pending p = pending_.front();
  pending_.pop_front();
  const GLenum waited = glClientWaitSync(p.fence, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(60e9));
  glDeleteSync(p.fence);
  if (waited == GL_TIMEOUT_EXPIRED || waited == GL_WAIT_FAILED) {
    throw RenderError(ErrorCode::kGraphics, "gl", "take_image: the frame's fence never signalled");
  }
  out.width = width_;
  out.height = height_;
  const std::size_t bytes = out.row_bytes() * static_cast<std::size_t>(height_);
  out.rgb.resize(bytes);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffers_[p.buffer].get());
  const void* mapped =
      glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(bytes), GL_MAP_READ_BIT);
  if (mapped == nullptr) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    throw RenderError(ErrorCode::kGraphics, "gl",
                      "take_image: the pixel buffer could not be mapped");
  }
  std::memcpy(out.rgb.data(), mapped, bytes);
  glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
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

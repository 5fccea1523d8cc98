// MP4 or GIF through the ffmpeg program: raw RGB24 frames go through a socket to its
// standard input (a socket rather than a pipe, so that a vanished ffmpeg is an error
// from send(), not a SIGPIPE), and it encodes them into a temporary file that
// finish() renames into place: H.264 (libx264, yuv420p, BT.709 matrix, sRGB transfer
// tagged) for MP4; for GIF, scaled down to VideoOptions::gif_width, one palette made
// from every frame (palettegen: ffmpeg holds the whole clip until the end, so GIFs are
// for short clips), applied with error diffusion, looping forever. Its standard error
// goes to a temporary log whose last line explains a failure.
#pragma once

#include <sys/types.h>

#include <string>

#include "render/video.hpp"
#include "temp_file.hpp"

namespace finflex::render::detail {

enum class FfmpegFormat { kMp4, kGif };

class FfmpegWriter : public VideoWriter {
 public:
  // Starts ffmpeg. kIo when it cannot be started.
  FfmpegWriter(const std::string& path, const VideoOptions& options,
               FfmpegFormat format = FfmpegFormat::kMp4);
  ~FfmpegWriter() override;
  void add_frame(const Image& frame) override;
  void finish() override;
  const std::string& path() const override { return file_.destination(); }
  std::size_t frame_count() const override { return frames_; }

 private:
  TempFile file_;
  TempFile log_;
  VideoOptions options_;
  pid_t child_ = -1;
  int input_ = -1;  // our end of ffmpeg's standard input
  std::size_t frames_ = 0;

  // Closes the input, waits for ffmpeg and returns its exit status (-1: not normal).
  int stop();
  [[noreturn]] void fail(const std::string& what);
};

// Whether `program` is an executable file in a folder of PATH.
bool on_path(const std::string& program);

}  // namespace finflex::render::detail

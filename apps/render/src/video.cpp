#include "render/video.hpp"

#include <algorithm>
#include <cctype>

#include "apng_writer.hpp"
#include "checks.hpp"
#include "ffmpeg_writer.hpp"
#include "render/error.hpp"

namespace finflex::render {

namespace {

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string extension = path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

void VideoOptions::validate() const {
  detail::require_in_range("video.width", width, 1, 16384);
  detail::require_in_range("video.height", height, 1, 16384);
  detail::require_in_range("video.fps", fps, 1, 240);
  detail::require_in_range("video.crf", crf, 0, 51);
  detail::require_in_range("video.png_compression", png_compression, 1, 9);
  detail::require_in_range("video.gif_width", gif_width, 0, 16384);
  detail::require_in_range("video.gif_colours", gif_colours, 2, 256);
  const char* presets[] = {"ultrafast", "superfast", "veryfast", "faster",  "fast",
                           "medium",    "slow",      "slower",   "veryslow"};
  if (std::find(std::begin(presets), std::end(presets), preset) == std::end(presets)) {
    detail::invalid("video.preset",
                    "\"" + preset + "\" is not an x264 preset (ultrafast .. veryslow)");
  }
}

void VideoOptions::check_frame(const Image& frame) const {
  frame.validate("frame");
  if (frame.width != width || frame.height != height) {
    throw RenderError(ErrorCode::kInvalidArgument, "frame",
                      "frame: " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                          ", the video is " + std::to_string(width) + "x" + std::to_string(height));
  }
}

bool ffmpeg_available() { return detail::on_path("ffmpeg"); }

std::unique_ptr<VideoWriter> open_video(const std::string& path, const VideoOptions& options) {
  options.validate();
  const std::string extension = lower_extension(path);
  if (extension == ".mp4" || extension == ".gif") {
    if (!ffmpeg_available()) {
      throw RenderError(ErrorCode::kIo, path,
                        "\"" + path + "\": " + (extension == ".mp4" ? "MP4" : "GIF") +
                            " needs the ffmpeg program, which is not on PATH "
                            "(write .png for an animated PNG instead)");
    }
    return std::make_unique<detail::FfmpegWriter>(
        path, options,
        extension == ".mp4" ? detail::FfmpegFormat::kMp4 : detail::FfmpegFormat::kGif);
  }
  if (extension == ".png" || extension == ".apng") {
    return std::make_unique<detail::ApngWriter>(path, options);
  }
  detail::invalid("path", "\"" + path + "\" does not end in .mp4, .gif, .png or .apng");
}

std::string default_video_path(const std::string& stem) {
  return stem + (ffmpeg_available() ? ".mp4" : ".png");
}

}  // namespace finflex::render

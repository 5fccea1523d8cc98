// Videos from frames: MP4 (H.264) through the `ffmpeg` program when it is installed,
// else an animated PNG (APNG) written here; animated GIF through ffmpeg too. All take
// whole RGB8 frames in order.
//
//   MP4: frames go raw through a pipe to ffmpeg (libx264, yuv420p, BT.709, sRGB
//        transfer tagged); small files, the encoder runs in its own process. Needs
//        `ffmpeg` on PATH.
//   GIF:  a preview: one palette (128 colours) for the whole clip, at most 400 pixels
//        wide, looping; a few hundred KB for a couple of seconds (a README's
//        animation), through ffmpeg.
//   APNG: every frame a whole PNG image (filtered rows, zlib deflate) in one file;
//        no dependency beyond zlib, lossless, but one to two orders of magnitude
//        larger than the MP4 and encoded on the calling thread.
// docs/rendering.md gives the measured cost of each.
//
// The file appears at its path only when finish() succeeds (written under a temporary
// name in the same folder, then renamed); a writer destroyed before finish(), or one
// whose finish() fails, leaves no file behind.
#pragma once

#include <memory>
#include <string>

#include "render/image.hpp"

namespace finflex::render {

struct VideoOptions {
  int width = 0;  // every frame's size
  int height = 0;
  int fps = 30;  // 1..240
  // MP4: x264's constant rate factor (0 lossless .. 51; 18-23 look good) and preset.
  int crf = 20;
  std::string preset = "veryfast";
  // APNG: zlib level, 1 (fast) .. 9 (small).
  int png_compression = 6;
  // GIF, a preview: frames wider than this are scaled down to it (Lanczos, aspect
  // kept); 0 keeps every frame's size. Colours: a palette of gif_colours (2 .. 256).
  int gif_width = 400;
  int gif_colours = 128;

  // Throws RenderError (kInvalidArgument) naming the field ("video.fps", ...).
  void validate() const;
  // Checks a frame for a video of these options: a valid image of width x height
  // (kInvalidArgument naming "frame" otherwise).
  void check_frame(const Image& frame) const;
};

class VideoWriter {
 public:
  virtual ~VideoWriter() = default;
  // Appends a frame; its size must be the options' (kInvalidArgument otherwise).
  virtual void add_frame(const Image& frame) = 0;
  // Completes the file and moves it into place. kIo on failure (e.g. ffmpeg's exit
  // status, with its last error line). At least one frame is needed.
  virtual void finish() = 0;
  virtual const std::string& path() const = 0;
  virtual std::size_t frame_count() const = 0;
};

// Whether an executable `ffmpeg` is on PATH.
bool ffmpeg_available();

// A writer chosen by the extension of `path`: ".mp4" or ".gif" through ffmpeg (kIo when
// it is not installed), ".png" or ".apng" an APNG; anything else is kInvalidArgument.
std::unique_ptr<VideoWriter> open_video(const std::string& path, const VideoOptions& options);

// stem + ".mp4" when ffmpeg is available, else stem + ".png" (an APNG).
std::string default_video_path(const std::string& stem);

}  // namespace finflex::render

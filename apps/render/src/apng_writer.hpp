// Animated PNG (APNG 1.0): every frame a whole 8-bit RGB image, rows filtered (the
// filter with the smallest sum of absolute differences, as libpng chooses) and
// deflated with zlib. The first frame is also the default image, so viewers without
// APNG show it as a still.
//
//   signature IHDR acTL sRGB | fcTL IDAT | fcTL fdAT | ... | IEND
//
// acTL holds the frame count, which is known only at the end: it is written as 0 and
// patched by finish().
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/video.hpp"
#include "temp_file.hpp"

namespace finflex::render::detail {

class ApngWriter : public VideoWriter {
 public:
  ApngWriter(const std::string& path, const VideoOptions& options);
  void add_frame(const Image& frame) override;
  void finish() override;
  const std::string& path() const override { return file_.destination(); }
  std::size_t frame_count() const override { return frames_; }

 private:
  TempFile file_;
  VideoOptions options_;
  std::size_t frames_ = 0;
  std::uint32_t sequence_ = 0;  // fcTL and fdAT numbers, shared and increasing
  bool finished_ = false;
  std::vector<std::uint8_t> filtered_;  // one filter byte + the row, per row
  std::vector<std::uint8_t> compressed_;
  std::vector<std::uint8_t> chunk_;

  void write_chunk(const char* type, const std::uint8_t* data, std::size_t size);
};

// Rows of `image` as PNG filtering leaves them for deflate (exposed for tests).
void filter_rows(const Image& image, std::vector<std::uint8_t>& out);

}  // namespace finflex::render::detail

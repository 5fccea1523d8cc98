#include "apng_writer.hpp"

#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "render/error.hpp"

namespace finflex::render::detail {

namespace {

constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::size_t kActlOffset = 8 + 25;  // after the signature and IHDR

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value >> 8));
  out.push_back(static_cast<std::uint8_t>(value & 0xff));
}

std::uint8_t paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a);
  const int pb = std::abs(p - b);
  const int pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(a);
  return static_cast<std::uint8_t>(pb <= pc ? b : c);
}

// The five PNG filters of one row (`above` is zeros for the first row).
void filter_row(int type, const std::uint8_t* row, const std::uint8_t* above, std::size_t bytes,
                std::uint8_t* out) {
  constexpr std::size_t kPixel = 3;
  for (std::size_t i = 0; i < bytes; ++i) {
    const int a = i >= kPixel ? row[i - kPixel] : 0;
    const int b = above[i];
    const int c = i >= kPixel ? above[i - kPixel] : 0;
    int predicted = 0;
    switch (type) {
      case 1:
        predicted = a;
        break;
      case 2:
        predicted = b;
        break;
      case 3:
        predicted = (a + b) / 2;
        break;
      case 4:
        predicted = paeth(a, b, c);
        break;
      default:
        break;
    }
    out[i] = static_cast<std::uint8_t>(row[i] - predicted);
  }
}

std::size_t cost(const std::uint8_t* filtered, std::size_t bytes) {
  std::size_t sum = 0;
  for (std::size_t i = 0; i < bytes; ++i)
    sum += static_cast<std::size_t>(std::abs(static_cast<std::int8_t>(filtered[i])));
  return sum;
}

}  // namespace

void filter_rows(const Image& image, std::vector<std::uint8_t>& out) {
  const std::size_t bytes = image.row_bytes();
  const auto rows = static_cast<std::size_t>(image.height);
  out.resize(rows * (bytes + 1));
  const std::vector<std::uint8_t> zeros(bytes, 0);
  std::vector<std::uint8_t> trial(bytes);
  for (std::size_t y = 0; y < rows; ++y) {
    const std::uint8_t* row = image.rgb.data() + y * bytes;
    const std::uint8_t* above = y > 0 ? row - bytes : zeros.data();
    std::uint8_t* target = out.data() + y * (bytes + 1);
    std::size_t best = static_cast<std::size_t>(-1);
    for (int type = 0; type < 5; ++type) {
      filter_row(type, row, above, bytes, trial.data());
      const std::size_t c = cost(trial.data(), bytes);
      if (c < best) {
        best = c;
        target[0] = static_cast<std::uint8_t>(type);
        std::memcpy(target + 1, trial.data(), bytes);
      }
    }
  }
}

ApngWriter::ApngWriter(const std::string& path, const VideoOptions& options)
    : file_(path), options_(options) {
  options_.validate();
  file_.write(kSignature, sizeof kSignature);
  std::vector<std::uint8_t> data;
  put_u32(data, static_cast<std::uint32_t>(options_.width));
  put_u32(data, static_cast<std::uint32_t>(options_.height));
  data.insert(data.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filters, no interlace
  write_chunk("IHDR", data.data(), data.size());
  data.clear();
  put_u32(data, 0);  // frames: patched by finish()
  put_u32(data, 0);  // plays: forever
  write_chunk("acTL", data.data(), data.size());
  const std::uint8_t perceptual = 0;
  write_chunk("sRGB", &perceptual, 1);
}

void ApngWriter::write_chunk(const char* type, const std::uint8_t* data, std::size_t size) {
  chunk_.clear();
  put_u32(chunk_, static_cast<std::uint32_t>(size));
  chunk_.insert(chunk_.end(), type, type + 4);
  chunk_.insert(chunk_.end(), data, data + size);
  const auto crc = crc32(0L, chunk_.data() + 4, static_cast<uInt>(size + 4));
  put_u32(chunk_, static_cast<std::uint32_t>(crc));
  file_.write(chunk_.data(), chunk_.size());
}

void ApngWriter::add_frame(const Image& frame) {
  options_.check_frame(frame);
  if (finished_) throw RenderError(ErrorCode::kInvalidArgument, "frame", "the video is finished");
  filter_rows(frame, filtered_);
  uLongf size = compressBound(static_cast<uLong>(filtered_.size()));
  compressed_.resize(4 + size);  // room for fdAT's sequence number in front
  if (compress2(compressed_.data() + 4, &size, filtered_.data(),
                static_cast<uLong>(filtered_.size()), options_.png_compression) != Z_OK) {
    throw RenderError(ErrorCode::kIo, path(), "\"" + path() + "\": deflate failed");
  }

  std::vector<std::uint8_t> control;
  put_u32(control, sequence_++);
  put_u32(control, static_cast<std::uint32_t>(options_.width));
  put_u32(control, static_cast<std::uint32_t>(options_.height));
  put_u32(control, 0);  // x offset
  put_u32(control, 0);  // y offset
  put_u16(control, 1);  // delay: 1 / fps seconds
  put_u16(control, static_cast<std::uint16_t>(options_.fps));
  control.push_back(0);  // dispose: none
  control.push_back(0);  // blend: source (the frame replaces the canvas)
  write_chunk("fcTL", control.data(), control.size());
  if (frames_ == 0) {
    write_chunk("IDAT", compressed_.data() + 4, size);
  } else {
    const std::uint32_t sequence = sequence_++;
    for (int k = 0; k < 4; ++k)
      compressed_[static_cast<std::size_t>(k)] =
          static_cast<std::uint8_t>(sequence >> (24 - 8 * k));
    write_chunk("fdAT", compressed_.data(), size + 4);
  }
  ++frames_;
}

void ApngWriter::finish() {
  if (frames_ == 0)
    throw RenderError(ErrorCode::kInvalidArgument, "frames", "a video needs a frame");
  write_chunk("IEND", nullptr, 0);
  // acTL's frame count, then its CRC over the type and the data.
  std::vector<std::uint8_t> actl{'a', 'c', 'T', 'L'};
  put_u32(actl, static_cast<std::uint32_t>(frames_));
  put_u32(actl, 0);
  std::vector<std::uint8_t> patch;
  put_u32(patch, static_cast<std::uint32_t>(frames_));
  put_u32(patch, 0);
  put_u32(patch,
          static_cast<std::uint32_t>(crc32(0L, actl.data(), static_cast<uInt>(actl.size()))));
  if (pwrite(file_.descriptor(), patch.data(), patch.size(), static_cast<off_t>(kActlOffset + 8)) !=
      static_cast<ssize_t>(patch.size())) {
    throw RenderError(ErrorCode::kIo, path(),
                      "\"" + path() + "\": write failed (" + std::strerror(errno) + ")");
  }
  file_.commit();
  finished_ = true;
}

}  // namespace finflex::render::detail

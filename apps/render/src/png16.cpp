#include "render/png16.hpp"

#include <zlib.h>

#include <cstdlib>

#include "checks.hpp"
#include "render/error.hpp"
#include "temp_file.hpp"

namespace finflex::render {

namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void put_chunk(std::vector<std::uint8_t>& out, const char* type,
               const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  const uLong crc = crc32(0L, out.data() + start, static_cast<uInt>(data.size() + 4));
  put_u32(out, static_cast<std::uint32_t>(crc));
}

std::size_t absolute_sum(const std::uint8_t* bytes, std::size_t count) {
  std::size_t sum = 0;
  for (std::size_t i = 0; i < count; ++i)
    sum += static_cast<std::size_t>(std::abs(static_cast<std::int8_t>(bytes[i])));
  return sum;
}

// Rows of big-endian samples, each behind its filter byte: None (0) or Sub (1, each
// byte minus the byte one pixel to its left), the one with the smaller absolute sum.
std::vector<std::uint8_t> filtered_rows(const Image16& image) {
  const auto width = static_cast<std::size_t>(image.width);
  const auto channels = static_cast<std::size_t>(image.channels);
  const std::size_t pixel = 2 * channels;
  const std::size_t row_bytes = width * pixel;
  std::vector<std::uint8_t> out;
  out.reserve(static_cast<std::size_t>(image.height) * (row_bytes + 1));
  std::vector<std::uint8_t> raw(row_bytes);
  std::vector<std::uint8_t> sub(row_bytes);
  for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y) {
    const std::uint16_t* row = image.samples.data() + y * width * channels;
    for (std::size_t k = 0; k < width * channels; ++k) {
      raw[2 * k] = static_cast<std::uint8_t>(row[k] >> 8);
      raw[2 * k + 1] = static_cast<std::uint8_t>(row[k] & 0xff);
    }
    for (std::size_t i = 0; i < row_bytes; ++i) {
      sub[i] = static_cast<std::uint8_t>(raw[i] - (i >= pixel ? raw[i - pixel] : 0));
    }
    const bool use_sub = absolute_sum(sub.data(), row_bytes) < absolute_sum(raw.data(), row_bytes);
    out.push_back(use_sub ? 1 : 0);
    const std::vector<std::uint8_t>& chosen = use_sub ? sub : raw;
    out.insert(out.end(), chosen.begin(), chosen.end());
  }
  return out;
}

}  // namespace

void Image16::validate(const char* field) const {
  detail::require_in_range(std::string(field) + ".width", width, 1, 1 << 24);
  detail::require_in_range(std::string(field) + ".height", height, 1, 1 << 24);
  if (channels != 1 && channels != 3) {
    detail::invalid(std::string(field) + ".channels", std::to_string(channels) + " is not 1 or 3");
  }
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                               static_cast<std::size_t>(channels);
  if (samples.size() != expected) {
    detail::invalid(
        std::string(field) + ".samples",
        std::to_string(samples.size()) + " values, expected " + std::to_string(expected));
  }
}

std::vector<std::uint8_t> encode_png16(const Image16& image) {
  image.validate();
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  put_u32(header, static_cast<std::uint32_t>(image.width));
  put_u32(header, static_cast<std::uint32_t>(image.height));
  // 16 bits, grey (0) or RGB (2), deflate, adaptive filters, no interlace.
  header.insert(header.end(),
                {16, static_cast<std::uint8_t>(image.channels == 1 ? 0 : 2), 0, 0, 0});
  put_chunk(png, "IHDR", header);
  const std::vector<std::uint8_t> rows = filtered_rows(image);
  uLongf size = compressBound(static_cast<uLong>(rows.size()));
  std::vector<std::uint8_t> compressed(size);
  if (compress2(compressed.data(), &size, rows.data(), static_cast<uLong>(rows.size()), 6) !=
      Z_OK) {
    throw RenderError(ErrorCode::kIo, "image", "deflate failed");
  }
  compressed.resize(size);
  put_chunk(png, "IDAT", compressed);
  put_chunk(png, "IEND", {});
  return png;
}

void write_png16(const std::string& path, const Image16& image) {
  const std::vector<std::uint8_t> png = encode_png16(image);
  detail::write_file_atomically(path, png.data(), png.size());
}

}  // namespace finflex::render

// A frame on the host: 8-bit sRGB-encoded RGB, rows from the top, no row padding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace finflex::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3 bytes

  std::size_t row_bytes() const { return static_cast<std::size_t>(width) * 3; }
  const std::uint8_t* pixel(int x, int y) const {
    return rgb.data() + static_cast<std::size_t>(y) * row_bytes() + static_cast<std::size_t>(x) * 3;
  }
  // Throws RenderError (kInvalidArgument, field `field`) unless width and height are
  // > 0 and rgb holds exactly width * height * 3 bytes.
  void validate(const char* field = "image") const;
};

}  // namespace finflex::render

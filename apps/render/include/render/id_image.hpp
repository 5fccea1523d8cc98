// The id pass's frame on the host (Renderer::render_ids): per pixel, the id of the
// fish instance whose surface is nearest the camera at the pixel's centre (0 where
// none is: the tank or the background), and that surface's depth.
//
// One sample per pixel, no antialiasing: a pixel belongs to a fish exactly when a
// triangle of the fish covers the pixel's centre (x + 0.5, y + 0.5) and nothing drawn
// is nearer there; the colour frame's edges are those pixels' multisampled blend.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace finflex::render {

struct IdImage {
  int width = 0;
  int height = 0;
  // Rows from the top, no padding: width * height values each.
  std::vector<std::uint32_t> ids;
  // Distance along the camera's view axis (metres) of the nearest surface drawn, the
  // tank's included; +infinity where nothing was drawn.
  std::vector<float> depth;

  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(x);
  }
};

}  // namespace finflex::render

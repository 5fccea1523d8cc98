#include "param_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace finflex::detail {

float float_bound(double bound) {
  float f = static_cast<float>(bound);
  if (static_cast<double>(f) > bound) f = std::nextafter(f, 0.0f);
  return f;
}

std::vector<float> bounds_tile(const std::vector<double>& bounds) {
  constexpr std::size_t kLanes = 16;
  std::vector<float> tile(bounds.size() * kLanes);
  for (std::size_t k = 0; k < tile.size(); ++k) tile[k] = float_bound(bounds[k % bounds.size()]);
  return tile;
}

namespace {

// One branch-free (vectorised) pass over the values; copies them when kCopy.
template <bool kCopy>
bool scan_bounds(const float* values, std::size_t count, const float* tile, std::size_t tile_length,
                 float* out) {
  int outside = 0;
  for (std::size_t start = 0; start < count; start += tile_length) {
    const std::size_t length = std::min(tile_length, count - start);
    const float* source = values + start;
    for (std::size_t k = 0; k < length; ++k) {
      if constexpr (kCopy) out[start + k] = source[k];
      outside |= !(std::fabs(source[k]) <= tile[k]);  // NaN compares false
    }
  }
  return outside == 0;
}

}  // namespace

bool within_bounds(const float* values, std::size_t count, const float* tile,
                   std::size_t tile_length) {
  return scan_bounds<false>(values, count, tile, tile_length, nullptr);
}

bool copy_if_within_bounds(const float* values, std::size_t count, const float* tile,
                           std::size_t tile_length, float* out) {
  return scan_bounds<true>(values, count, tile, tile_length, out);
}

}  // namespace finflex::detail

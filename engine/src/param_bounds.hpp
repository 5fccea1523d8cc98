// The fast path of the per-frame parameter checks: one vectorisable pass that copies
// the values and tells whether every one is finite and within its bound. Only when it
// says no do the callers walk the values again to clamp them or to name the bad one.
#pragma once

#include <cstddef>
#include <vector>

namespace finflex::detail {

// The largest float f with f <= bound, so that for a float v,
// |v| <= f (in float) exactly when |v| <= bound (in double).
float float_bound(double bound);

// Per-value bounds for rows of bounds.size() values, the row repeated a whole number
// of times to a multiple of 16 floats (SIMD lanes): the `tile` below.
std::vector<float> bounds_tile(const std::vector<double>& bounds);

// Copies values[0, count) to out and returns true when |values[k]| <= tile[k % tile_length]
// for every k (false for NaN and infinities). tile_length is a multiple of the row length.
bool copy_if_within_bounds(const float* values, std::size_t count, const float* tile,
                           std::size_t tile_length, float* out);

}  // namespace finflex::detail

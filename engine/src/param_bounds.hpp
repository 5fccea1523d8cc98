// The fast path of the per-frame parameter checks: one vectorisable pass that copies
// the values and tells whether every one is finite and within its bound. Only when it
// says no do the callers walk the values again to clamp them or to name the bad one.
#pragma once

#include <cstddef>
#include <vector>

#include "finflex/rig_deformer.hpp"

namespace finflex::detail {

// The largest float f with f <= bound, so that for a float v,
// |v| <= f (in float) exactly when |v| <= bound (in double).
float float_bound(double bound);

// Per-value bounds for rows of bounds.size() values, the row repeated a whole number
// of times to a multiple of 16 floats (SIMD lanes): the `tile` below.
std::vector<float> bounds_tile(const std::vector<double>& bounds);

// True when |values[k]| <= tile[k % tile_length] for every k in [0, count) (false for
// NaN and infinities). tile_length is a multiple of the row length.
bool within_bounds(const float* values, std::size_t count, const float* tile,
                   std::size_t tile_length);

// The same, copying values[0, count) to out on the way.
bool copy_if_within_bounds(const float* values, std::size_t count, const float* tile,
                           std::size_t tile_length, float* out);

// A rig's checks with its bounds tile computed once (rig_bounds_tile of its
// rig_param_limits): the vectorised pass, then, only when it fails,
// check_rig_params to clamp or to name the bad value.
std::vector<float> rig_bounds_tile(const std::vector<double>& limits);
void check_rig_params_into(const Rig& rig, const std::vector<double>& limits,
                           const std::vector<float>& tile, const RigParameters& parameters,
                           bool clamp, std::vector<float>& out);
void check_rig_params(const Rig& rig, const std::vector<double>& limits,
                      const std::vector<float>& tile, const RigParameters& parameters, bool clamp);

}  // namespace finflex::detail

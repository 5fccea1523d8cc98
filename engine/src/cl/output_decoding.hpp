// A batch's outputs read back to the host in any layout and format, decoded to float
// planes.
#pragma once

#include <cstddef>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"

namespace finflex::detail {

// Blocking read of every attribute of `batch` into float planes of `vertices` a plane
// (the batch's vertex order; the caller sets slot_of_vertex for slot order).
DeformedBatch<float> read_outputs(Context& context, const DeviceBatch& batch, std::size_t vertices);

}  // namespace finflex::detail

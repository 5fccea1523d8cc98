// A batch's output buffers on the device (finflex/device_batch.hpp): made (allocated,
// the caller's buffers, or over the caller's host memory), checked against a deformer's
// vertex count and the layout, and host batches mapped for reading.
#pragma once

#include <cstddef>
#include <string>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/output_layout.hpp"

namespace finflex::detail {

// Checks that `batch` holds `counts.instance_count` instances of `vertices` vertices
// (slots or mesh vertices, as its order says) in its layout, in buffers large enough,
// tangents only for a mesh that has them. kInvalidArgument naming `field` (e.g.
// "job.outputs") and the rule broken.
void check_outputs(const DeviceBatch& batch, std::size_t vertices, bool mesh_tangents,
                   const std::string& field);

// A batch of `counts` in `outputs`: buffers allocated (one per attribute, sized by the
// layout), the caller's buffers, or buffers over the caller's host memory. Checked as
// check_outputs does, naming "outputs".
DeviceBatch allocate_outputs(Context& context, const BatchShape& counts,
                             const OutputLayout& outputs, std::size_t vertices);
DeviceBatch bind_outputs(Context& context, const BatchShape& counts, const OutputLayout& outputs,
                         const OutputBuffers& buffers, std::size_t vertices);
DeviceBatch bind_host_outputs(Context& context, const BatchShape& counts,
                              const OutputLayout& outputs, const HostOutputs& host,
                              std::size_t vertices);

// Host batches: map their buffers for reading on the host (blocking: the caller's
// memory holds the frame when it returns), and unmap them before the next frame.
void map_host_outputs(Context& context, DeviceBatch& batch);
void unmap_host_outputs(Context& context, DeviceBatch& batch);

}  // namespace finflex::detail

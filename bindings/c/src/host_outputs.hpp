// Caller-owned host outputs (finflex_host_outputs): their checks, and the copy of a
// deformed batch into them.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "handles.hpp"

namespace finflex::c {

// Throws kInvalidArgument naming "outputs.<attribute>.<field>" and the values when an
// attribute given (data not NULL) cannot hold `instances` x `vertices` float32 xyz
// elements (format, alignment, strides, capacity), or tangents are asked of a mesh
// without them. `outputs` itself must not be null.
void check_outputs(const finflex_host_outputs* outputs, std::size_t instances, std::size_t vertices,
                   bool mesh_has_tangents);

// The element (instance, vertex) of an attribute described by `layout` (checked).
glm::vec3 load_element(const finflex_attribute_layout& layout, std::size_t instance,
                       std::size_t vertex);

// Writes every instance of `batch` (mesh vertex order) into the checked `outputs`.
void store_outputs(const finflex::DeformedBatch<float>& batch, const finflex_host_outputs& outputs);
void store_outputs(const finflex::DeformedBatch<double>& batch,
                   const finflex_host_outputs& outputs);

}  // namespace finflex::c

// One deformed instance of a batch as a whole mesh (to write a file, or to hand to a
// renderer that wants interleaved host data).
#pragma once

#include <cstddef>

#include "finflex/batch.hpp"
#include "finflex/export.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

// The rest mesh with positions, normals and (when both have them) tangents replaced
// by those of `instance` in `batch`; faces, vertex order, texcoords and tangent
// handedness are the rest mesh's. Throws kInvalidArgument naming `instance` when it
// is out of range or the batch does not belong to a mesh of this vertex count.
FINFLEX_API Mesh instance_mesh(const Mesh& rest, const DeformedBatch<float>& batch,
                               std::size_t instance);
FINFLEX_API Mesh instance_mesh(const Mesh& rest, const DeformedBatch<double>& batch,
                               std::size_t instance);

}  // namespace finflex

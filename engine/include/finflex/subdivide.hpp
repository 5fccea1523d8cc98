// Loop subdivision (OpenMesh), for making dense meshes from a coarse cage, e.g. a
// 100k-vertex fish from data/blub/fish_control_mesh.obj for benchmarks.
#pragma once

#include "finflex/export.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

// Subdivides the triangle mesh `levels` times with Loop's scheme (each level splits
// every triangle into four and smooths). The result has positions, indices and
// normals recomputed from its faces; texcoords, tangents and groups are not carried.
// Throws kInvalidMesh when the mesh is invalid or has no triangles, kInvalidArgument
// naming "levels" when it is outside [0, 8].
FINFLEX_API Mesh subdivide_loop(const Mesh& mesh, int levels);

}  // namespace finflex

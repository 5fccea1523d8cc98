// The secant-surface transform of one vertex in its stage's frame, in double
// precision (METHOD.md section 4): the CPU reference's building block, shared by
// every deformer (each only gives the surface at x, a SecantSample).
#pragma once

#include <glm/glm.hpp>

#include "finflex/deformer_type.hpp"
#include "finflex/job.hpp"
#include "finflex/reference.hpp"

namespace finflex::detail {

using Vertex = LocalVertex;

// (7) for the position, p' = f(x, y, 0) + z n; (8) (the Rodrigues rotation taking
// e_z to n) or the Jacobian's cofactor for the normal; R or J for the tangent.
Vertex apply_secant(const Vertex& rest, const SecantSample& s, NormalMode normals);

}  // namespace finflex::detail

// A synthetic fish-like test mesh already in its body frame (the identity frame):
// a closed spindle along x in [-0.5, 0.5] (head at +x), elliptic cross-sections taller
// (y) than wide (z), with analytic-free normals computed from the faces.
#pragma once

#include "finflex/mesh.hpp"

namespace finflex::test {

// rings: cross-sections along x (>= 3); segments: vertices per cross-section (>= 3).
// with_tangents: adds unit tangents along the rings' x direction, w = +1.
Mesh synthetic_fish(int rings = 48, int segments = 32, bool with_tangents = false);

// A flat ribbon in the secant plane: two rows of `samples` vertices at y = 0 (the
// spine, vertices [0, samples)) and y = width, x uniform in [-half_length, half_length].
Mesh spine_ribbon(int samples, double half_length, double width = 0.01);

}  // namespace finflex::test

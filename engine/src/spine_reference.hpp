// The secant-surface deformers of one vertex in its stage frame, literally as
// METHOD.md writes them, in double precision: the CPU reference's building blocks.
#pragma once

#include <glm/glm.hpp>

#include "finflex/bend.hpp"
#include "finflex/reference_deformer.hpp"

namespace finflex::detail {

// The secant surface along the spine at one x: f(x, 0), df/dx, the unit normal n and
// dn/dx (for the Jacobian). y passes through unchanged: df/dy = e_y (16).
struct SpineSample {
  glm::dvec3 f;
  glm::dvec3 df_dx;
  glm::dvec3 n;
  glm::dvec3 dn_dx;
};

// Paper bend (15)-(17).
SpineSample paper_spine(double x, double m);
// Exact bend: the closed form of (13).
SpineSample exact_spine(double x, double m);
// Hinge: the spine's angle ramps linearly from 0 at x = 0 to `angle` at x = width
// (a step at 0 when width = 0); x < 0 untouched (METHOD.md section 6).
SpineSample hinge_spine(double x, double angle, double width);

// (7) for positions; (8) (Rodrigues rotation taking e_z to n) or the Jacobian's
// cofactor for normals; R or J for tangents.
LocalVertex apply_spine(const LocalVertex& rest, const SpineSample& s, NormalMode normals);

}  // namespace finflex::detail

// Occlusion by tank walls, for the level choice (finflex/level_choice.hpp): a fish
// behind the wall of another tank is hidden from a camera and need not be deformed or
// drawn.
//
// A wall is a vertical prism (world +y up) of `sides` flat faces inscribed in the
// circle of `radius` about the floor's centre `base`, from the floor to `height` above
// it, drawn from inside only (its faces face the axis, as a renderer's cut-away tank
// draws it: the half nearer a camera outside is culled). A line of sight is blocked
// where it leaves the prism through a face: at a point of its boundary between the
// floor and the rim, before the point it looks at.
//
// wall_hides_sphere is conservative: true only when every line of sight from the eye to
// every point of the sphere is blocked. It bounds, in the horizontal plane, the wedge of
// directions to the sphere's disc (half-angle asin(r / d) about the direction to its
// centre, d the horizontal distance); where the eye is outside the wall, every direction
// of the wedge must meet the circle inscribed in the faces, radius cos(pi / sides) times
// the wall's. The exit distance t along a direction at angle phi from the direction to
// the axis, t(phi) = m cos phi + sqrt(R^2 - m^2 sin^2 phi) (m the eye's distance from the
// axis), falls as phi grows; a face's exit lies between the inscribed and the outer
// circle's, so over the wedge it lies within [t_in(phi_max), t_out(phi_min)]. Blocked
// needs t_out(phi_min) < d - r (the wall before the sphere), and the height of the
// sight line there, e_y + (q_y - e_y) t / t_q for sphere points q at horizontal distance
// t_q in [d - r, d + r] and height q_y in [c_y - r, c_y + r], within [0, height] at the
// four corners of those ranges (the height is bilinear in q_y and t / t_q).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "finflex/export.hpp"

namespace finflex {

struct FINFLEX_API WallOccluder {
  glm::dvec3 base{0.0};  // the floor's centre, in the world (+y up)
  double radius = 1.0;   // the circle the faces' edges lie on (> 0)
  double height = 1.0;   // floor to rim (> 0)
  int sides = 0;         // faces around, >= 3; 0: a true cylinder

  // The radius of the circle inscribed in the faces: radius cos(pi / sides).
  double inner_radius() const;

  // kInvalidArgument naming `field` and the part: a non-finite base, a radius or height
  // not > 0, sides 1 or 2 or below 0.
  void validate(const std::string& field) const;
};

// Whether `wall` hides every point of the sphere (centre, radius > 0) from `eye`, in
// double precision (the device's test is the same in float).
FINFLEX_API bool wall_hides_sphere(const glm::dvec3& eye, const glm::dvec3& centre, double radius,
                                   const WallOccluder& wall);

}  // namespace finflex

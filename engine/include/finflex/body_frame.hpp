// The local frame of a transform (METHOD.md section 3, the paper's (1)-(2)).
//
//   e_x  along the spine, head towards +x
//   e_y  dorsal (up); xOy is the secant (sagittal) plane
//   e_z  lateral, e_z = e_x x e_y (right-handed)
//   origin  the pivot: the point that stays fixed while the body bends
//   length  s_x, the body's extent along e_x; local lengths are divided by it
//
// Going in (2): p = M p_b with M = T S R_b, i.e. p = R_b (p_b - origin) / length;
// normals n = R_b n_b. Going out uses M^-1.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "finflex/mesh.hpp"

namespace finflex {

struct BodyFrame {
  glm::dvec3 origin{0.0};
  glm::dvec3 axis_x{1.0, 0.0, 0.0};
  glm::dvec3 axis_y{0.0, 1.0, 0.0};
  glm::dvec3 axis_z{0.0, 0.0, 1.0};
  double length = 1.0;

  // The mesh coordinates already are the local frame: no rotation, translation or scale.
  static BodyFrame identity() { return BodyFrame{}; }

  glm::dvec3 point_to_local(const glm::dvec3& p) const;
  glm::dvec3 point_to_mesh(const glm::dvec3& p) const;
  glm::dvec3 vector_to_local(const glm::dvec3& v) const;  // directions: rotation only
  glm::dvec3 vector_to_mesh(const glm::dvec3& v) const;

  // Throws finflex::Error (kInvalidArgument) naming the field when the axes are not
  // finite, not unit, not orthogonal or not right-handed, or length is not > 0.
  void validate() const;
};

// Overrides for the automatic frame; each one left empty is found from the mesh.
struct FrameOptions {
  std::optional<glm::dvec3> head_direction;    // roughly towards the head; sign of e_x
  std::optional<glm::dvec3> dorsal_direction;  // roughly towards the back; sign of e_y
  std::optional<glm::dvec3> pivot;             // the fixed point, in mesh coordinates
};

// Finds the body frame of an arbitrarily oriented fish:
//  1. axes: principal axes of the surface (area-weighted covariance of the triangles):
//     largest extent -> spine e_x, middle -> dorsal-ventral e_y, smallest -> lateral e_z;
//  2. head: the end of the spine whose outer third is thicker laterally (RMS of the
//     lateral coordinate): a fish tapers to a thin peduncle and a flat caudal fin;
//  3. dorsal: the side with the larger third moment (skewness) along e_y, i.e. the
//     side that reaches farther from the centre, as the dorsal fin does;
//  4. pivot: the area-weighted surface centroid;
//  5. length: the extent of the vertices along e_x.
// The result is equivariant: rotating and translating the mesh rotates and translates
// the frame with it. Throws kInvalidMesh when the mesh has no area or its principal
// axes are degenerate (e.g. a sphere), asking for explicit options.
BodyFrame find_body_frame(const Mesh& mesh, const FrameOptions& options = {});

}  // namespace finflex

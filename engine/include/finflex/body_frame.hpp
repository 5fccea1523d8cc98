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

#include "finflex/export.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

struct FINFLEX_API BodyFrame {
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

  // Throws finflex::Error (kInvalidArgument) naming the field ("origin", "axis_x",
  // "axis_y", "axis_z", "length") and its value when: origin is not finite; an axis is
  // not finite or not unit (| |axis| - 1 | > 1e-6); two axes are not orthogonal
  // (|dot| > 1e-6, names the later one); the axes are left-handed ("axis_z"); length
  // is not finite and > 0.
  void validate() const;
};

// Overrides for the automatic frame; each one left empty is found from the mesh.
struct FrameOptions {
  std::optional<glm::dvec3> head_direction;    // roughly towards the head; sign of e_x
  std::optional<glm::dvec3> dorsal_direction;  // roughly towards the back; picks e_y
  std::optional<glm::dvec3> pivot;             // the fixed point, in mesh coordinates
};

// Finds the body frame of an arbitrarily oriented fish. Moments are exact integrals
// over the triangles (area-weighted), taken about the surface centroid mu.
//  1. spine e_x: the principal axis of the surface with the largest second moment;
//  2. lateral e_z and dorsal e_y: of the two other principal axes, the lateral one is
//     the one the surface faces most (larger area-weighted mean of (n . axis)^2 over the
//     unit face normals n: flanks and flat median fins face sideways); the other one is
//     dorsal. Not "the middle moment is dorsal": Blub is about as wide as tall and its
//     bent tail makes its lateral moment the middle one. With dorsal_direction given,
//     the principal axis closer to it (larger |cos|) is e_y instead;
//  3. head (sign of e_x): split the vertices' extent along e_x in thirds; the end whose
//     outer third (triangles by their centroid) has the larger area-weighted RMS of the
//     e_z coordinate about mu is the head: a fish tapers to a thin peduncle and a flat
//     caudal fin. head_direction instead: the sign of its dot with e_x;
//  4. dorsal (sign of e_y): the positive third moment (skewness) along e_y, i.e. the
//     side that reaches farther from the centre, as the dorsal fin does.
//     dorsal_direction instead: the sign of its dot with e_y. Then e_z = e_x x e_y;
//  5. origin: pivot if given (must be finite), else mu;
//  6. length: the extent of the vertices along e_x (max - min of (p - origin) . e_x).
// Checked on the bundled fish (glTF node transforms applied): Blub, both resolutions,
// and the Barramundi come out with the head at mesh +z and the back at mesh +y.
// The result is equivariant: rotating and translating the mesh rotates and translates
// the frame with it (exact ties, e.g. a fish symmetric end to end, keep an arbitrary
// sign: give the option).
// Errors: the mesh fails validate_mesh() (kInvalidMesh naming its field); kInvalidMesh
// with field "mesh" when the mesh has no area, its two largest second moments are
// within a relative 1e-3 (no spine, e.g. a sphere: give the frame explicitly), or its
// two smaller ones are (a round cross-section) and no dorsal_direction is given (with
// it, e_y is dorsal_direction made perpendicular to e_x); kInvalidArgument naming
// "options.head_direction" / "options.dorsal_direction" when zero, not finite, or
// within |cos| < 1e-3 of perpendicular to the axis it orients, "options.pivot" when
// not finite.
FINFLEX_API BodyFrame find_body_frame(const Mesh& mesh, const FrameOptions& options = {});

}  // namespace finflex

// World placement of an instance: the last stage of a deformation, a rigid motion and
// a uniform scale, so outputs come out in world space (e.g. fish in a tank).
//
// Convention: the instance's body frame (the rig's root frame, METHOD.md section 3:
// e_x towards the head, e_y dorsal, e_z to the fish's right, the origin at the pivot)
// is placed with its origin at `position`, its axes turned by `orientation` (a unit
// quaternion taking body axes to world axes), and scaled so that the body's length s_x
// becomes `length`. World units are the caller's; FinFlex's tank uses metres, y up.
//
//   world(p) = position + orientation * (length / s_x) * R_body (p - origin_body)
//   world direction(d) = orientation * R_body d       (normals and tangents)
#pragma once

#include <array>
#include <cstddef>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "finflex/export.hpp"

namespace finflex {

struct Placement {
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z: no rotation
  float length = 1.0f;                            // > 0, world units
};

// What the kernels read per instance, 16 floats: the columns of L Q (the orientation
// scaled by the length, 9 values), the position (3), 1 / L (1), 3 unused. It places
// points given in the body frame's local coordinates (METHOD.md (2): lengths in body
// lengths), which is where a rig's last stage leaves every vertex:
//   world(p_local) = position + L Q p_local,   world(d_local) = (L Q d_local) / L.
// It does not depend on the mesh, so one record places any rig's instance.
constexpr std::size_t kPlacementFloats = 16;
using PlacementRecord = std::array<float, kPlacementFloats>;

// The record of `placement`. kInvalidArgument naming "placement.length" (not finite and
// > 0) or "placement.orientation" (not a finite unit quaternion within 1e-3) or
// "placement.position" (not finite).
FINFLEX_API PlacementRecord placement_record(const Placement& placement);

// A placed point and direction in body-local coordinates (the record applied), for
// tests and tools.
FINFLEX_API glm::dvec3 place_point(const PlacementRecord& record, const glm::dvec3& p);
FINFLEX_API glm::dvec3 place_direction(const PlacementRecord& record, const glm::dvec3& d);

}  // namespace finflex

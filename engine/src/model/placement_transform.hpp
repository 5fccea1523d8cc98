// World placement in double precision (finflex/placement.hpp): what the reference
// applies, from mesh coordinates (the kernels' records place body-local coordinates:
// the same map, composed with (2)).
#pragma once

#include <glm/glm.hpp>

#include "finflex/body_frame.hpp"
#include "finflex/placement.hpp"

namespace finflex::detail {

struct PlacementTransform {
  glm::dmat3 m{1.0};           // orientation * (length / s_x) * R_body
  glm::dvec3 t{0.0};           // position - m origin_body
  double inverse_scale = 1.0;  // s_x / length

  glm::dvec3 point(const glm::dvec3& p) const { return m * p + t; }
  glm::dvec3 direction(const glm::dvec3& d) const { return m * d * inverse_scale; }
};

// Validates `placement` (errors as placement_record's); its orientation as a matrix.
glm::dmat3 checked_rotation(const Placement& placement);

// Validates `placement` and composes it with `body`: mesh coordinates to the world.
PlacementTransform placement_transform(const Placement& placement, const BodyFrame& body);

}  // namespace finflex::detail

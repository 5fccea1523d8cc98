#include "finflex/placement.hpp"

#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "finflex/error.hpp"
#include "model/placement_transform.hpp"

namespace finflex {
namespace {

[[noreturn]] void fail(const char* field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, std::string(field) + " " + message);
}

}  // namespace

namespace detail {

glm::dmat3 checked_rotation(const Placement& placement) {
  const glm::vec3& p = placement.position;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    fail("placement.position", "is not finite");
  }
  if (!std::isfinite(placement.length) || !(placement.length > 0.0f)) {
    fail("placement.length", "= " + std::to_string(placement.length) + " must be finite and > 0");
  }
  const glm::dquat q(placement.orientation);
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!std::isfinite(norm) || std::fabs(norm - 1.0) > 1e-3) {
    fail("placement.orientation", "is not a unit quaternion (|q| = " + std::to_string(norm) + ")");
  }
  return glm::mat3_cast(glm::normalize(q));
}

PlacementTransform placement_transform(const Placement& placement, const BodyFrame& body) {
  const glm::dmat3 rotation = checked_rotation(placement);
  // R_body: rows are the body axes, so R_body v gives body coordinates.
  const glm::dmat3 body_rotation =
      glm::transpose(glm::dmat3(body.axis_x, body.axis_y, body.axis_z));
  const double scale = double(placement.length) / body.length;
  const glm::dmat3 m = rotation * body_rotation * scale;
  const glm::dvec3 t = glm::dvec3(placement.position) - m * body.origin;
  return {m, t, 1.0 / scale};
}

}  // namespace detail

PlacementRecord placement_record(const Placement& placement) {
  const glm::dmat3 scaled = detail::checked_rotation(placement) * double(placement.length);
  PlacementRecord record{};
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) record[std::size_t(3 * c + r)] = static_cast<float>(scaled[c][r]);
    record[std::size_t(9 + c)] = placement.position[c];
  }
  record[12] = static_cast<float>(1.0 / double(placement.length));
  return record;
}

glm::dvec3 place_point(const PlacementRecord& r, const glm::dvec3& p) {
  return glm::dvec3(r[9], r[10], r[11]) + p.x * glm::dvec3(r[0], r[1], r[2]) +
         p.y * glm::dvec3(r[3], r[4], r[5]) + p.z * glm::dvec3(r[6], r[7], r[8]);
}

glm::dvec3 place_direction(const PlacementRecord& r, const glm::dvec3& d) {
  return (d.x * glm::dvec3(r[0], r[1], r[2]) + d.y * glm::dvec3(r[3], r[4], r[5]) +
          d.z * glm::dvec3(r[6], r[7], r[8])) *
         double(r[12]);
}

}  // namespace finflex

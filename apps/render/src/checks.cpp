#include "checks.hpp"

#include <cmath>
#include <sstream>

#include "render/error.hpp"

namespace finflex::render::detail {

void invalid(const std::string& field, const std::string& why) {
  throw RenderError(ErrorCode::kInvalidArgument, field, field + ": " + why);
}

std::string to_text(float value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string to_text(const glm::vec3& value) {
  return "(" + to_text(value.x) + ", " + to_text(value.y) + ", " + to_text(value.z) + ")";
}

void require_finite(const std::string& field, float value) {
  if (!std::isfinite(value)) invalid(field, to_text(value) + " is not finite");
}

void require_finite(const std::string& field, const glm::vec3& value) {
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(value[c])) invalid(field, to_text(value) + " is not finite");
  }
}

void require_positive(const std::string& field, float value) {
  require_finite(field, value);
  if (!(value > 0.0f)) invalid(field, to_text(value) + " is not > 0");
}

void require_non_negative(const std::string& field, const glm::vec3& value) {
  require_finite(field, value);
  for (int c = 0; c < 3; ++c) {
    if (value[c] < 0.0f) invalid(field, to_text(value) + " has a negative component");
  }
}

void require_in_range(const std::string& field, float value, float low, float high) {
  require_finite(field, value);
  if (value < low || value > high) {
    invalid(field, to_text(value) + " is outside " + to_text(low) + " .. " + to_text(high));
  }
}

void require_in_range(const std::string& field, int value, int low, int high) {
  if (value < low || value > high) {
    invalid(field, std::to_string(value) + " is outside " + std::to_string(low) + " .. " +
                       std::to_string(high));
  }
}

}  // namespace finflex::render::detail

// Argument checks shared by the renderer's validate() functions: each throws
// RenderError (kInvalidArgument) naming the field and the value.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace finflex::render::detail {

[[noreturn]] void invalid(const std::string& field, const std::string& why);

std::string to_text(float value);
std::string to_text(const glm::vec3& value);

void require_finite(const std::string& field, float value);
void require_finite(const std::string& field, const glm::vec3& value);
void require_positive(const std::string& field, float value);                 // finite, > 0
void require_non_negative(const std::string& field, const glm::vec3& value);  // finite, >= 0
void require_in_range(const std::string& field, float value, float low, float high);
void require_in_range(const std::string& field, int value, int low, int high);

}  // namespace finflex::render::detail

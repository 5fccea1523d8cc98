#include "render/image.hpp"

#include <string>

#include "checks.hpp"

namespace finflex::render {

void Image::validate(const char* field) const {
  const std::string name = field;
  detail::require_in_range(name + ".width", width, 1, 1 << 16);
  detail::require_in_range(name + ".height", height, 1, 1 << 16);
  const std::size_t expected = row_bytes() * static_cast<std::size_t>(height);
  if (rgb.size() != expected) {
    detail::invalid(name + ".rgb", std::to_string(rgb.size()) + " bytes, expected " +
                                       std::to_string(expected) + " (width * height * 3)");
  }
}

}  // namespace finflex::render

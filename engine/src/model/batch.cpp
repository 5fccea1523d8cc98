#include "finflex/batch.hpp"

#include "finflex/error.hpp"

namespace finflex {

std::size_t padded_plane_stride(std::size_t vertex_count) {
  constexpr std::size_t kAlignment =
      64;  // elements: 256 bytes in float, a multiple of any cache line
  return (vertex_count + kAlignment - 1) / kAlignment * kAlignment;
}

const char* to_string(NormalFormat format) {
  return format == NormalFormat::kHalf ? "half" : "float32";
}

NormalFormat parse_normal_format(const std::string& text, const std::string& field) {
  if (text == "float32") return NormalFormat::kFloat32;
  if (text == "half") return NormalFormat::kHalf;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not a normal format (expected float32 or half)");
}

}  // namespace finflex

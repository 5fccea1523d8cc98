#include "finflex/batch.hpp"

namespace finflex {

std::size_t padded_plane_stride(std::size_t vertex_count) {
  constexpr std::size_t kAlignment =
      64;  // elements: 256 bytes in float, a multiple of any cache line
  return (vertex_count + kAlignment - 1) / kAlignment * kAlignment;
}

}  // namespace finflex

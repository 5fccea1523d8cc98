#include "render/png.hpp"

#include "render/error.hpp"
#include "temp_file.hpp"

// stb_image_write with every function static, so that no other copy in the program
// (e.g. a mesh library's) can clash with it.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace finflex::render {

namespace {

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image) {
  image.validate();
  std::vector<std::uint8_t> png;
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 3, image.rgb.data(),
                             static_cast<int>(image.row_bytes())) == 0) {
    throw RenderError(ErrorCode::kIo, "image", "PNG encoding failed");
  }
  return png;
}

void write_png(const std::string& path, const Image& image) {
  const std::vector<std::uint8_t> png = encode_png(image);
  detail::write_file_atomically(path, png.data(), png.size());
}

}  // namespace finflex::render

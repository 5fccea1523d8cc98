// PNG files of frames.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace finflex::render {

// The PNG encoding of `image` (stb_image_write; 8-bit RGB).
std::vector<std::uint8_t> encode_png(const Image& image);

// Writes `image` as a PNG: to a temporary file in the same folder, renamed into place,
// so `path` is either the old file or the whole new one, never a part. Errors
// (RenderError): kInvalidArgument for a bad image, kIo naming `path` when the folder is
// missing or the write fails (the temporary file is removed).
void write_png(const std::string& path, const Image& image);

}  // namespace finflex::render

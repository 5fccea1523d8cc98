// 16-bit PNG files: instance masks (grey, one id per pixel) and vertex animation
// textures (RGB, quantised positions and normals). Lossless; samples are stored
// big-endian, as PNG requires, and read back exactly by any PNG reader that keeps
// 16 bits: stb_image's stbi_load_16, OpenCV's IMREAD_UNCHANGED, imageio; Pillow keeps
// them for grey ("I;16") but reduces RGB to 8 bits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace finflex::render {

struct Image16 {
  int width = 0;
  int height = 0;
  int channels = 1;                    // 1: grey; 3: RGB
  std::vector<std::uint16_t> samples;  // width * height * channels, rows from the top

  // Throws RenderError (kInvalidArgument, field `field`) unless the sizes are > 0,
  // channels is 1 or 3 and samples holds exactly width * height * channels values.
  void validate(const char* field = "image") const;
};

// The PNG encoding (colour type 0 or 2, bit depth 16; each row filtered by None or
// Sub, whichever sums to less; zlib level 6).
std::vector<std::uint8_t> encode_png16(const Image16& image);

// Writes it whole or not at all, as write_png does.
void write_png16(const std::string& path, const Image16& image);

}  // namespace finflex::render

// The instances of an id image (render::IdImage, one id per pixel) as COCO wants them:
// per id its pixel count (the visible area), its tight bounding box and its mask as
// run-length counts.
//
// COCO's run-length encoding: the mask's pixels in column-major order (down the first
// column, then the next), as alternating runs of 0s and 1s starting with 0s (the first
// count may be 0); the counts sum to width * height.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/id_image.hpp"

namespace finflex::pictures {

struct InstanceMask {
  std::uint32_t id = 0;
  std::size_t area = 0;  // pixels
  int x_min = 0;         // the box: pixels x_min..x_max, y_min..y_max (inclusive)
  int y_min = 0;
  int x_max = 0;
  int y_max = 0;
  std::vector<std::uint32_t> counts;  // COCO run lengths, column-major
};

// Every id > 0 present in the image, ascending; one pass over the pixels. Work and
// memory: the pixels, plus the largest id present, plus two counts per run.
std::vector<InstanceMask> instance_masks(const render::IdImage& image);

// pycocotools' compact form of run-length counts (maskApi.c rleToString): each count,
// minus the count two before it from the third on, in 5-bit groups, least significant
// first, each group + 48 as a character, 0x20 set on all but a number's last group.
std::string compress_counts(const std::vector<std::uint32_t>& counts);

}  // namespace finflex::pictures

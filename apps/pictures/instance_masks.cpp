#include "instance_masks.hpp"

#include <algorithm>
#include <string>

namespace finflex::pictures {

std::vector<InstanceMask> instance_masks(const render::IdImage& image) {
  std::uint32_t largest = 0;
  for (std::uint32_t id : image.ids) largest = std::max(largest, id);
  // Per id, its mask's slot (or none) and where its last run ended (column-major).
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::uint32_t> slot(std::size_t{largest} + 1, kNone);
  std::vector<std::size_t> run_end;
  std::vector<InstanceMask> masks;

  const std::size_t pixels = image.ids.size();
  const auto height = static_cast<std::size_t>(image.height);
  std::uint32_t current = 0;  // the id of the run being read
  std::size_t run_start = 0;
  const auto close_run = [&](std::size_t end) {
    if (current == 0) return;
    std::uint32_t& s = slot[current];
    if (s == kNone) {
      s = static_cast<std::uint32_t>(masks.size());
      InstanceMask mask;
      mask.id = current;
      mask.x_min = image.width;
      mask.y_min = image.height;
      mask.x_max = -1;
      mask.y_max = -1;
      masks.push_back(std::move(mask));
      run_end.push_back(0);
    }
    InstanceMask& mask = masks[s];
    mask.counts.push_back(static_cast<std::uint32_t>(run_start - run_end[s]));  // 0s before
    mask.counts.push_back(static_cast<std::uint32_t>(end - run_start));         // the 1s
    mask.area += end - run_start;
    run_end[s] = end;
    // A run lies in one column or spans several: its box covers every pixel of it.
    const auto first_x = static_cast<int>(run_start / height);
    const auto last_x = static_cast<int>((end - 1) / height);
    mask.x_min = std::min(mask.x_min, first_x);
    mask.x_max = std::max(mask.x_max, last_x);
    if (first_x == last_x) {
      mask.y_min = std::min(mask.y_min, static_cast<int>(run_start % height));
      mask.y_max = std::max(mask.y_max, static_cast<int>((end - 1) % height));
    } else {
      mask.y_min = 0;
      mask.y_max = image.height - 1;
    }
  };
  for (std::size_t k = 0; k < pixels; ++k) {
    const std::size_t x = k / height;
    const std::size_t y = k % height;
    const std::uint32_t id = image.ids[image.index(static_cast<int>(x), static_cast<int>(y))];
    if (id != current) {
      close_run(k);
      current = id;
      run_start = k;
    }
  }
  close_run(pixels);
  for (std::size_t s = 0; s < masks.size(); ++s) {
    masks[s].counts.push_back(static_cast<std::uint32_t>(pixels - run_end[s]));  // 0s after
  }
  std::sort(masks.begin(), masks.end(),
            [](const InstanceMask& a, const InstanceMask& b) { return a.id < b.id; });
  return masks;
}

std::string compress_counts(const std::vector<std::uint32_t>& counts) {
  std::string text;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    long long x = counts[i];
    if (i > 2) x -= counts[i - 2];
    bool more = true;
    while (more) {
      char c = static_cast<char>(x & 0x1f);
      x >>= 5;  // arithmetic: a negative difference keeps its sign
      more = (c & 0x10) ? x != -1 : x != 0;
      if (more) c = static_cast<char>(c | 0x20);
      text.push_back(static_cast<char>(c + 48));
    }
  }
  return text;
}

}  // namespace finflex::pictures

#include "lens.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "finflex/error.hpp"
#include "split_mix.hpp"

namespace finflex::pictures {

glm::dvec2 LensDistortion::distort(glm::dvec2 p) const {
  const double r2 = glm::dot(p, p);
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {p.x * radial + 2.0 * p1 * p.x * p.y + p2 * (r2 + 2.0 * p.x * p.x),
          p.y * radial + p1 * (r2 + 2.0 * p.y * p.y) + 2.0 * p2 * p.x * p.y};
}

glm::dvec2 LensDistortion::undistort(glm::dvec2 d) const {
  // Fixed point of p = (d - tangential(p)) / radial(p), as cv::undistortPoints.
  glm::dvec2 p = d;
  for (int k = 0; k < 100; ++k) {
    const double r2 = glm::dot(p, p);
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const glm::dvec2 tangential{2.0 * p1 * p.x * p.y + p2 * (r2 + 2.0 * p.x * p.x),
                                p1 * (r2 + 2.0 * p.y * p.y) + 2.0 * p2 * p.x * p.y};
    const glm::dvec2 next = (d - tangential) / radial;
    if (glm::length(next - p) < 1e-12) return next;
    p = next;
  }
  return p;
}

LensWarp::LensWarp(const LensDistortion& distortion, const render::PinholeIntrinsics& k, int width,
                   int height, const std::string& field)
    : distortion_(distortion), k_(k), width_(width), height_(height) {
  source_.resize(std::size_t(width) * std::size_t(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec2 d{(x + 0.5 - k.cx) / k.fx, (y + 0.5 - k.cy) / k.fy};
      const glm::dvec2 p = distortion.undistort(d);
      if (glm::length(distortion.distort(p) - d) > 1e-9 || !std::isfinite(p.x + p.y)) {
        throw Error(ErrorCode::kInvalidArgument, field,
                    field + ": the distortion does not invert at pixel (" + std::to_string(x) +
                        ", " + std::to_string(y) + "): too strong for this image");
      }
      source_[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
          glm::vec2(float(k.fx * p.x + k.cx), float(k.fy * p.y + k.cy));
    }
  }
}

glm::dvec2 LensWarp::distort_pixel(glm::dvec2 ideal) const {
  const glm::dvec2 d = distortion_.distort({(ideal.x - k_.cx) / k_.fx, (ideal.y - k_.cy) / k_.fy});
  return {k_.fx * d.x + k_.cx, k_.fy * d.y + k_.cy};
}

void LensWarp::apply(const render::Image& ideal, render::Image& out) const {
  out.width = width_;
  out.height = height_;
  out.rgb.assign(std::size_t(width_) * std::size_t(height_) * 3, 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      // Bilinear between the four ideal pixel centres around the source.
      const glm::vec2 s = source_[std::size_t(y) * std::size_t(width_) + std::size_t(x)] - 0.5f;
      const int x0 = int(std::floor(s.x)), y0 = int(std::floor(s.y));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= width_ || y0 + 1 >= height_) continue;
      const float fx = s.x - float(x0), fy = s.y - float(y0);
      std::uint8_t* to =
          out.rgb.data() + (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
      for (int c = 0; c < 3; ++c) {
        const float top = (1 - fx) * ideal.pixel(x0, y0)[c] + fx * ideal.pixel(x0 + 1, y0)[c];
        const float bottom =
            (1 - fx) * ideal.pixel(x0, y0 + 1)[c] + fx * ideal.pixel(x0 + 1, y0 + 1)[c];
        to[c] = std::uint8_t(std::lround((1 - fy) * top + fy * bottom));
      }
    }
  }
}

void LensWarp::apply(const render::IdImage& ids, render::IdImage& out) const {
  out.width = width_;
  out.height = height_;
  out.ids.assign(ids.ids.size(), 0);  // reuses out's storage
  out.depth.assign(ids.depth.size(), std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t>& id = out.ids;
  std::vector<float>& depth = out.depth;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const glm::vec2 s = source_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
      const int sx = int(std::floor(s.x)), sy = int(std::floor(s.y));
      if (sx < 0 || sy < 0 || sx >= width_ || sy >= height_) continue;
      const std::uint32_t here = ids.ids[ids.index(sx, sy)];
      id[ids.index(x, y)] = here;
      depth[ids.index(x, y)] = ids.depth[ids.index(sx, sy)];
      // Within one surface, the depth between the four pixel centres around the source,
      // bilinear in 1 / depth (exact on a plane: 1 / depth is linear in the image).
      const glm::vec2 c = s - 0.5f;
      const int x0 = int(std::floor(c.x)), y0 = int(std::floor(c.y));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= width_ || y0 + 1 >= height_) continue;
      float inverse[4];
      bool same = true;
      for (int k = 0; k < 4; ++k) {
        const std::size_t at = ids.index(x0 + (k & 1), y0 + (k >> 1));
        same = same && ids.ids[at] == here && std::isfinite(ids.depth[at]) && ids.depth[at] > 0;
        inverse[k] = same ? 1.0f / ids.depth[at] : 0.0f;
      }
      if (!same) continue;
      const float fx = c.x - float(x0), fy = c.y - float(y0);
      const float top = (1 - fx) * inverse[0] + fx * inverse[1];
      const float bottom = (1 - fx) * inverse[2] + fx * inverse[3];
      depth[ids.index(x, y)] = 1.0f / ((1 - fy) * top + fy * bottom);
    }
  }
}

void SensorNoise::apply(render::Image& image, std::uint64_t seed) const {
  float sigma[256];  // per value: its standard deviation
  for (int v = 0; v < 256; ++v) sigma[v] = float(std::sqrt(read * read + shot * shot * v / 255.0));
  SplitMix random{seed};
  const auto add = [&](std::uint8_t& value, double normal) {
    value = std::uint8_t(std::clamp(std::lround(value + sigma[value] * normal), 0L, 255L));
  };
  // Box-Muller: two standard normal deviates from two uniforms.
  const double two_pi = 6.283185307179586;
  std::size_t k = 0;
  for (; k + 1 < image.rgb.size(); k += 2) {
    const double radius = std::sqrt(-2.0 * std::log(1.0 - random.uniform()));
    const double angle = two_pi * random.uniform();
    add(image.rgb[k], radius * std::cos(angle));
    add(image.rgb[k + 1], radius * std::sin(angle));
  }
  if (k < image.rgb.size()) {
    add(image.rgb[k],
        std::sqrt(-2.0 * std::log(1.0 - random.uniform())) * std::cos(two_pi * random.uniform()));
  }
}

}  // namespace finflex::pictures

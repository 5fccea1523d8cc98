// A real camera's image from the renderer's ideal pinhole image: lens distortion in
// OpenCV's (Brown-Conrady) model and sensor noise. Applied to the picture and its
// truth alike (masks, depth, keypoints), never to the geometry.
//
// Distortion, as cv::projectPoints applies it to a point's normalised coordinates
// (x, y) = (X / Z, Y / Z), r^2 = x^2 + y^2:
//   x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y_d = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
//   u = fx x_d + cx,  v = fy y_d + cy.
// The distorted image samples the ideal one where each of its pixel centres comes
// from: the inverse of the model, iterated as cv::undistortPoints does (to 1e-9 of a
// normalised unit), bilinear for colour, nearest for ids, and for depth bilinear in
// 1 / depth between the four pixels around the source where they are one surface
// (nearest elsewhere: at a silhouette's edge). A pixel whose
// source lies outside the ideal frame is black, id 0, depth infinite (nothing).
//
// Noise, per pixel and channel on the sRGB-encoded value I (0..255), seeded by the
// frame: I + N(0, read^2 + shot^2 I / 255), rounded and clamped: read noise and a
// shot-noise term that grows with the signal (sigma = shot at full scale); the normal
// deviates by Box-Muller from splitmix64 (the same on every platform).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/camera.hpp"
#include "render/id_image.hpp"
#include "render/image.hpp"

namespace finflex::pictures {

struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;  // OpenCV's order
  bool none() const { return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0; }
  glm::dvec2 distort(glm::dvec2 normalised) const;
  // The normalised point that distort() takes to `distorted`.
  glm::dvec2 undistort(glm::dvec2 distorted) const;
};

// For images of width x height pixels seen with `k`: each distorted pixel's source.
// kInvalidArgument naming `field` when the model does not invert over the image (the
// iteration does not converge at a pixel, or its inverse maps back elsewhere).
class LensWarp {
 public:
  LensWarp(const LensDistortion& distortion, const render::PinholeIntrinsics& k, int width,
           int height, const std::string& field);
  // Pixel coordinates (u, v) of the ideal image to the distorted image's.
  glm::dvec2 distort_pixel(glm::dvec2 ideal) const;
  void apply(const render::Image& ideal, render::Image& out) const;
  void apply(const render::IdImage& ids, render::IdImage& out) const;  // ids and depth

 private:
  LensDistortion distortion_;
  render::PinholeIntrinsics k_;
  int width_, height_;
  std::vector<glm::vec2> source_;  // per distorted pixel, its ideal pixel position
};

struct SensorNoise {
  double read = 0.0;  // sRGB levels
  double shot = 0.0;  // sRGB levels at full scale
  bool none() const { return read == 0.0 && shot == 0.0; }
  void apply(render::Image& image, std::uint64_t seed) const;
};

}  // namespace finflex::pictures

// The swim cycle as vertex animation textures (VAT) for engines whose shaders read
// textures in the vertex stage (Unity, Unreal, Godot, three.js): every frame's
// positions and normals quantised to 16 bits per channel in two RGB PNGs, with a JSON
// of what decodes them and a GLSL snippet that does.
//
// Layout: vertex v of frame k is texel (v mod W, k R + floor(v / W)), W = min(vertex
// count, max_width) columns, R = ceil(vertex count / W) rows per frame, N R rows in all.
// Encoding (per channel, q in 0..65535, read back by a shader as q / 65535):
//   position p = bounds_min + (q / 65535) (bounds_max - bounds_min)   (the bounds of every
//             frame's positions; quantisation error at most half a step,
//             (bounds_max - bounds_min) / 131070 per axis)
//   normal   n = normalize(2 q / 65535 - 1)                          (error <= 1 / 65535 per
//             component before normalising)
// The textures hold data, not colour: import them as linear (not sRGB), uncompressed,
// 16 bits, nearest filtering, no mipmaps.
//
// Files (stem = the species' name): <stem>_vat_positions.png, <stem>_vat_normals.png,
// <stem>_vat.json (sizes, bounds, period, the formula), <stem>_vat.glsl (the decoding
// functions) and <stem>_vat_mesh.glb (the rest pose in the textures' vertex order, with
// TEXCOORD_1 = ((v mod W + 0.5) / W, floor(v / W)) for shaders without vertex ids).
#pragma once

#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "finflex/mesh.hpp"
#include "swim_cycle.hpp"

namespace finflex::bake {

struct VatLayout {
  std::size_t width = 0;           // W
  std::size_t rows_per_frame = 0;  // R
  std::size_t height = 0;          // N R
  glm::vec3 bounds_min{0.0f};
  glm::vec3 bounds_max{0.0f};
};

// W, R and the positions' bounds of `baked`'s frames. kInvalidArgument naming
// "max_width" when it is 0 or above 16384.
VatLayout vat_layout(const BakedCycle& baked, std::size_t max_width);

// Writes the five files into `folder`. finflex::Error kIo.
VatLayout write_vertex_animation_texture(const std::string& folder, const std::string& stem,
                                         const Mesh& mesh, const BakedCycle& baked,
                                         std::size_t max_width);

}  // namespace finflex::bake

// Private: the glTF reader's two halves. mesh_io_gltf_load.cpp turns bytes into a
// tinygltf::Model, guarding tinygltf against what it trusts (GLB chunk lengths, JSON
// nesting, non-regular files behind URIs); mesh_io_gltf.cpp flattens the model's
// scene into a Mesh.
#pragma once

#include <tiny_gltf.h>  // implementation compiled into libtinygltf (Debian package)

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::io {

// kFormat naming a glTF field ("meshes[0].primitives[1].indices"): "<field>: <message>".
[[noreturn]] inline void throw_gltf_format(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kFormat, field, field + ": " + message);
}

// "array[index]", a glTF field's name.
inline std::string indexed(const std::string& array, std::size_t index) {
  return array + "[" + std::to_string(index) + "]";
}

// JSON arrays and objects may nest at most this deep (a glTF file needs about 8
// levels, extras and extensions included); deeper text is refused before tinygltf
// parses it, whose handling of extras recurses once per level.
constexpr std::size_t kMaxJsonDepth = 64;

// Scene nodes may nest at most this deep (root nodes are at depth 1).
constexpr std::size_t kMaxNodeDepth = 1024;

// The flattened scene may hold at most this many vertices, indices and group-name
// bytes together per byte of input (the file and its buffers): instancing a mesh
// from many nodes cannot make work and memory grow faster than the input.
constexpr std::uint64_t kPlacedElementsPerInputByte = 4;

struct LoadedGltf {
  tinygltf::Model model;
  std::uint64_t input_bytes = 0;  // the file's bytes plus those of every buffer loaded
};

// Parses `bytes` as GLB (if they start with "glTF") or as glTF JSON. Relative URIs
// resolve against `base_dir`; only regular files are read through them; images are
// not decoded. Throws kFormat (bad layout, nesting beyond kMaxJsonDepth, tinygltf's
// errors) or kIo (a buffer file that is missing or cannot be read).
LoadedGltf load_gltf_model(std::string_view bytes, const std::string& base_dir);

// Accessors (mesh_io_gltf_accessor.cpp). Accessor `index` is bounds-checked against
// its bufferView and buffer; one without bufferView (all zeros) may have at most as
// many elements as the input has bytes; sparse ones are not supported. `field` names
// the referring property ("meshes[0].primitives[1].NORMAL"). Throws kFormat, or
// kInvalidMesh for a non-finite value naming the element ("...POSITION[1].y").

// count * components floats of an accessor of `type` (TINYGLTF_TYPE_VEC3, ...): float
// components, and with `allow_normalized` normalized unsigned byte / short (mapped to
// [0, 1]).
std::vector<float> read_floats(const LoadedGltf& gltf, int index, int type, bool allow_normalized,
                               const std::string& field);

// A SCALAR accessor of unsigned byte, short or int components.
std::vector<std::uint32_t> read_indices(const LoadedGltf& gltf, int index,
                                        const std::string& field);

// Scene nodes (mesh_io_gltf_nodes.cpp).

// A node of the scene, and the position of its parent in the same list (-1 for a
// root).
struct PlacedNode {
  std::size_t node = 0;
  std::int64_t parent = -1;
};

// The nodes of the scene (the default scene, else scene 0, else every node without a
// parent) in depth-first pre-order, children in listed order: each once, parents
// before their children. Throws kFormat naming the node unless the hierarchy is a
// forest: every child exists; no node is listed twice or by two parents; no cycle;
// scene nodes exist, are listed once and are roots; no node deeper than
// kMaxNodeDepth. Work is linear in the number of nodes and children; no recursion.
std::vector<PlacedNode> scene_nodes(const tinygltf::Model& model);

}  // namespace finflex::io

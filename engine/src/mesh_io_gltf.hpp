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

namespace finflex::io {

// JSON arrays and objects may nest at most this deep (a glTF file needs about 8
// levels, extras and extensions included); deeper text is refused before tinygltf
// parses it, whose handling of extras recurses once per level.
constexpr std::size_t kMaxJsonDepth = 64;

struct LoadedGltf {
  tinygltf::Model model;
  std::uint64_t input_bytes = 0;  // the file's bytes plus those of every buffer loaded
};

// Parses `bytes` as GLB (if they start with "glTF") or as glTF JSON. Relative URIs
// resolve against `base_dir`; only regular files are read through them; images are
// not decoded. Throws kFormat (bad layout, nesting beyond kMaxJsonDepth, tinygltf's
// errors) or kIo (a buffer file that is missing or cannot be read).
LoadedGltf load_gltf_model(std::string_view bytes, const std::string& base_dir);

}  // namespace finflex::io

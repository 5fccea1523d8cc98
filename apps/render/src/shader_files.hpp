// The GLSL files of apps/render/shaders/, embedded at build time by
// cmake/embed_shaders.cmake (generated shader_files.cpp).
#pragma once

#include <string>
#include <vector>

namespace finflex::render::detail {

struct ShaderFile {
  const char* name;  // file name, e.g. "fish.vert.glsl"
  const char* text;
};

const std::vector<ShaderFile>& shader_files();

// The text of the file `name`; throws RenderError (kGraphics) when it is not embedded.
const char* shader_file(const std::string& name);

}  // namespace finflex::render::detail

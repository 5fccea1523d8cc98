// A linked GLSL program made of embedded files: each stage is "#version 330 core",
// a "#define NAME 1" per define, then its files in order (shared blocks and
// functions first).
#pragma once

#include <string>
#include <vector>

#include "gl_object.hpp"

namespace finflex::render::detail {

// The defines of the programs that bend the view rays at the water surface
// (Scene::view_refraction: FINFLEX_REFRACTION, shaders/refraction.glsl), or none.
inline std::vector<std::string> refraction_defines(bool refraction) {
  if (!refraction) return {};
  return {"FINFLEX_REFRACTION"};
}

class ShaderProgram {
 public:
  // Throws RenderError (kGraphics) with the driver's log when a stage does not compile
  // or the program does not link; `name` says which program.
  ShaderProgram(const std::string& name, const std::vector<std::string>& vertex_files,
                const std::vector<std::string>& fragment_files,
                const std::vector<std::string>& defines = {});

  GLuint get() const { return program_.get(); }
  void use() const { glUseProgram(program_.get()); }
  // The uniform's location; -1 when the program has none of that name (or it is unused).
  GLint uniform(const char* name) const { return glGetUniformLocation(program_.get(), name); }
  // Binds the uniform block `block`, when the program uses it, to `binding`.
  void bind_block(const char* block, GLuint binding) const;
  // Points the sampler uniform `name` at texture unit `unit` (once, after linking).
  void bind_sampler(const char* name, GLint unit) const;

 private:
  GlProgram program_;
};

}  // namespace finflex::render::detail

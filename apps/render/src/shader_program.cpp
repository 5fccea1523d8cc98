#include "shader_program.hpp"

#include "render/error.hpp"
#include "shader_files.hpp"

namespace finflex::render::detail {

namespace {

std::string info_log(GLuint object, bool is_program) {
  GLint length = 0;
  if (is_program) {
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  } else {
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  }
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  if (is_program) {
    glGetProgramInfoLog(object, length, nullptr, log.data());
  } else {
    glGetShaderInfoLog(object, length, nullptr, log.data());
  }
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  return log;
}

GlShader compile(const std::string& program, GLenum type, const std::vector<std::string>& files,
                 const std::vector<std::string>& defines) {
  std::string text = "#version 330 core\n";
  for (const std::string& define : defines) text += "#define " + define + " 1\n";
  for (const std::string& file : files) text += shader_file(file);
  GlShader shader = GlShader::create(type);
  const char* source = text.c_str();
  glShaderSource(shader.get(), 1, &source, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw RenderError(ErrorCode::kGraphics, program,
                      "shader program " + program + ": " + files.back() +
                          " does not compile: " + info_log(shader.get(), false));
  }
  return shader;
}

}  // namespace

const char* shader_file(const std::string& name) {
  for (const ShaderFile& file : shader_files()) {
    if (name == file.name) return file.text;
  }
  throw RenderError(ErrorCode::kGraphics, name, "shader file " + name + " is not embedded");
}

ShaderProgram::ShaderProgram(const std::string& name, const std::vector<std::string>& vertex_files,
                             const std::vector<std::string>& fragment_files,
                             const std::vector<std::string>& defines) {
  const GlShader vertex = compile(name, GL_VERTEX_SHADER, vertex_files, defines);
  const GlShader fragment = compile(name, GL_FRAGMENT_SHADER, fragment_files, defines);
  program_ = GlProgram::create();
  glAttachShader(program_.get(), vertex.get());
  glAttachShader(program_.get(), fragment.get());
  glLinkProgram(program_.get());
  glDetachShader(program_.get(), vertex.get());
  glDetachShader(program_.get(), fragment.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw RenderError(
        ErrorCode::kGraphics, name,
        "shader program " + name + " does not link: " + info_log(program_.get(), true));
  }
}

void ShaderProgram::bind_block(const char* block, GLuint binding) const {
  const GLuint index = glGetUniformBlockIndex(program_.get(), block);
  if (index != GL_INVALID_INDEX) glUniformBlockBinding(program_.get(), index, binding);
}

void ShaderProgram::bind_sampler(const char* name, GLint unit) const {
  use();
  glUniform1i(uniform(name), unit);
}

}  // namespace finflex::render::detail

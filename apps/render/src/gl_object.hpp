// Owning handles of GL objects: move-only, deleted with their kind's glDelete* when the
// handle goes. The context they belong to must be current and must outlive them (the
// renderer declares its EGL context before every GL object).
#pragma once

#include <utility>

#include <epoxy/gl.h>

namespace finflex::render::detail {

template <typename Kind>
class GlObject {
 public:
  GlObject() = default;
  // Creates a new object of this kind (glGen* / glCreate*).
  template <typename... Args>
  static GlObject create(Args... args) {
    GlObject object;
    object.name_ = Kind::create(args...);
    return object;
  }
  ~GlObject() { reset(); }
  GlObject(GlObject&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;

  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_ != 0) Kind::destroy(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

struct BufferKind {
  static GLuint create() {
    GLuint name = 0;
    glGenBuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteBuffers(1, &name); }
};

struct TextureKind {
  static GLuint create() {
    GLuint name = 0;
    glGenTextures(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteTextures(1, &name); }
};

struct VertexArrayKind {
  static GLuint create() {
    GLuint name = 0;
    glGenVertexArrays(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteVertexArrays(1, &name); }
};

struct FramebufferKind {
  static GLuint create() {
    GLuint name = 0;
    glGenFramebuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteFramebuffers(1, &name); }
};

struct RenderbufferKind {
  static GLuint create() {
    GLuint name = 0;
    glGenRenderbuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteRenderbuffers(1, &name); }
};

struct ShaderKind {
  static GLuint create(GLenum type) { return glCreateShader(type); }
  static void destroy(GLuint name) { glDeleteShader(name); }
};

struct ProgramKind {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint name) { glDeleteProgram(name); }
};

struct QueryKind {
  static GLuint create() {
    GLuint name = 0;
    glGenQueries(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteQueries(1, &name); }
};

// GL_EXT_memory_object and GL_EXT_semaphore: memory and semaphores of another API.
struct MemoryObjectKind {
  static GLuint create() {
    GLuint name = 0;
    glCreateMemoryObjectsEXT(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteMemoryObjectsEXT(1, &name); }
};

struct SemaphoreKind {
  static GLuint create() {
    GLuint name = 0;
    glGenSemaphoresEXT(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteSemaphoresEXT(1, &name); }
};

using GlBuffer = GlObject<BufferKind>;
using GlQuery = GlObject<QueryKind>;
using GlMemoryObject = GlObject<MemoryObjectKind>;
using GlSemaphore = GlObject<SemaphoreKind>;
using GlTexture = GlObject<TextureKind>;
using GlVertexArray = GlObject<VertexArrayKind>;
using GlFramebuffer = GlObject<FramebufferKind>;
using GlRenderbuffer = GlObject<RenderbufferKind>;
using GlShader = GlObject<ShaderKind>;
using GlProgram = GlObject<ProgramKind>;

}  // namespace finflex::render::detail

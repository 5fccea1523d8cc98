#include "external_objects.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

#include "render/error.hpp"

namespace finflex::render::detail {
namespace {

void invalid(const std::string& field, const std::string& value) {
  throw RenderError(ErrorCode::kInvalidArgument, field, field + ": " + value);
}

void refused(const char* call) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  throw RenderError(ErrorCode::kGraphics, "gl", std::string(call) + " failed: GL error " + code);
}

}  // namespace

ExternalSupport query_external_support() {
  ExternalSupport out;
  out.memory = epoxy_has_gl_extension("GL_EXT_memory_object") &&
               epoxy_has_gl_extension("GL_EXT_memory_object_fd");
  out.semaphores =
      epoxy_has_gl_extension("GL_EXT_semaphore") && epoxy_has_gl_extension("GL_EXT_semaphore_fd");
  if (!out.memory) {
    out.why_not = "OpenGL has no GL_EXT_memory_object_fd";
    return out;
  }
  GLint count = 0;
  glGetIntegerv(GL_NUM_DEVICE_UUIDS_EXT, &count);
  for (GLint k = 0; k < count; ++k) {
    std::array<std::uint8_t, 16> uuid{};
    glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, static_cast<GLuint>(k), uuid.data());
    out.device_uuids.push_back(uuid);
  }
  glGetError();  // a driver without the UUID queries: no UUIDs, nothing else lost
  return out;
}

ImportedBuffer import_buffer(int fd, std::size_t memory_bytes, std::size_t bytes) {
  if (fd < 0) invalid("fd", std::to_string(fd) + " is not a file descriptor");
  if (bytes == 0 || bytes > memory_bytes) {
    close(fd);
    invalid("bytes", std::to_string(bytes) + (bytes == 0 ? "" : " is more than the memory's ") +
                         (bytes == 0 ? "" : std::to_string(memory_bytes)));
  }
  ImportedBuffer out;
  out.memory = GlMemoryObject::create();
  const GLint dedicated = GL_TRUE;
  glMemoryObjectParameterivEXT(out.memory.get(), GL_DEDICATED_MEMORY_OBJECT_EXT, &dedicated);
  glImportMemoryFdEXT(out.memory.get(), static_cast<GLuint64>(memory_bytes),
                      GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
  refused("glImportMemoryFdEXT");
  out.buffer = GlBuffer::create();
  glBindBuffer(GL_COPY_WRITE_BUFFER, out.buffer.get());
  glBufferStorageMemEXT(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(bytes), out.memory.get(), 0);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  refused("glBufferStorageMemEXT");
  return out;
}

GlSemaphore import_semaphore(int fd) {
  if (fd < 0) invalid("fd", std::to_string(fd) + " is not a file descriptor");
  GlSemaphore out = GlSemaphore::create();
  glImportSemaphoreFdEXT(out.get(), GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
  refused("glImportSemaphoreFdEXT");
  return out;
}

}  // namespace finflex::render::detail

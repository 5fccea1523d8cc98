// OpenGL's side of external memory (GL_EXT_memory_object_fd, GL_EXT_semaphore_fd):
// buffers whose storage is memory another API exported, and semaphores another API
// signals or waits for. What the renderer offers (Renderer::external_support) is read
// once from the context.
#pragma once

#include <cstddef>
#include <string>

#include <epoxy/gl.h>

#include "gl_object.hpp"
#include "render/renderer.hpp"

namespace finflex::render::detail {

// The current context's extensions and device UUIDs.
ExternalSupport query_external_support();

// Imports `fd` (owned by GL from the call on, also when it fails) as a dedicated
// memory object of `memory_bytes`, and a buffer of `bytes` stored in it.
// Errors (RenderError kInvalidArgument naming "fd", "bytes"; kGraphics when GL
// refuses): a negative fd, bytes 0 or over memory_bytes.
struct ImportedBuffer {
  GlMemoryObject memory;
  GlBuffer buffer;
};
ImportedBuffer import_buffer(int fd, std::size_t memory_bytes, std::size_t bytes);
GlSemaphore import_semaphore(int fd);

}  // namespace finflex::render::detail

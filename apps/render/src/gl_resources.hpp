// What the renderer keeps on the device between frames, and the driver limits the
// fish pass plans its draws by.
#pragma once

#include <cstddef>

#include "external_objects.hpp"
#include "gl_object.hpp"

namespace finflex::render::detail {

constexpr GLuint kPatternLocation = 5;  // fish.vert.glsl's a_pattern

// A species' triangles: an element buffer recorded in a vertex array whose only
// per-vertex attribute is the pattern, when given (positions and normals come from
// buffer textures).
struct MeshResources {
  GlVertexArray vertex_array;
  GlBuffer indices;
  GLsizei index_count = 0;
  std::size_t vertex_count = 0;
  GlBuffer pattern;  // per vertex (u, v): attribute 5, when patterned
  bool patterned = false;
};

// A buffer of Renderer::create_buffer, or of import_buffer (then its memory object:
// declared first, so that the buffer goes before the memory it is stored in).
struct BufferResource {
  GlMemoryObject memory;
  GlBuffer buffer;
  std::size_t bytes = 0;
};

struct GlLimits {
  std::size_t max_buffer_texels = 0;        // GL_MAX_TEXTURE_BUFFER_SIZE
  std::size_t buffer_offset_alignment = 1;  // GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT
  bool texture_buffer_range = false;        // glTexBufferRange (GL 4.3, ARB_texture_buffer_range)
  bool draw_indirect = false;               // glDrawElementsIndirect (GL 4.0, ARB_draw_indirect)
  int max_samples = 1;
};

}  // namespace finflex::render::detail

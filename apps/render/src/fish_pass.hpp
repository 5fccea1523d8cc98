// Draws fish: one glDrawElementsInstanced per FishDraw (more when its vertex data is
// larger than one buffer texture can address), with no per-vertex attributes: the
// vertex shader fetches positions and normals from buffer textures (samplerBuffer,
// GL 3.1) by gl_VertexID and gl_InstanceID, as the stream's layout says; the
// instance's transform is an instanced attribute (a mat4, divisor 1). Host streams
// and transforms are copied into buffers kept from frame to frame (orphaned on each
// upload); streams in the renderer's buffers are read in place.
//
// Two outputs: lit colour (the scene's shading, into the colour pass's framebuffer)
// or ids (each instance's FishDraw::ids value as an instanced attribute, written to
// the id pass's unsigned integer target).
//
// Splitting: a buffer texture addresses at most GL_MAX_TEXTURE_BUFFER_SIZE texels
// (2^27 on Mesa and NVIDIA: 4,000 instances of a 10,816-slot fish is 1.3e8 floats per
// attribute). Where glTexBufferRange exists, a draw goes in runs of instances whose
// elements fit one range; without it a draw must fit whole (else kGraphics).
#pragma once

#include <cstddef>
#include <vector>

#include "gl_resources.hpp"
#include "render/fish_draw.hpp"
#include "shader_program.hpp"

namespace finflex::render::detail {

enum class FishOutput { kLitColour, kIds };

class FishPass {
 public:
  FishPass(const GlLimits& limits, FishOutput output);
  // `fish` passed validate_fish(). Needs the scene framebuffer bound and the Scene
  // block at binding 0.
  void draw(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
            const std::vector<BufferResource>& buffers);

 private:
  // A stream as drawn: the GL buffer that holds it, its size, its layout.
  struct Stream {
    GLuint buffer = 0;
    std::size_t bytes = 0;
    StreamLayout layout;
  };

  GlLimits limits_;
  FishOutput output_;
  ShaderProgram program_;
  GlTexture positions_;
  GlTexture normals_;
  std::vector<GlBuffer> uploads_;  // four per draw: positions, normals, transforms, ids
  GLint position_stream_ = -1;
  GLint normal_stream_ = -1;
  GLint albedo_ = -1;
  GLuint transform_buffer_ = 0;  // this draw's uploads of instanced attributes; 0: none
  GLuint id_buffer_ = 0;

  GLuint upload(std::size_t slot, const void* data, std::size_t bytes);
  Stream prepare(const VertexStream& stream, std::size_t instances, std::size_t vertices,
                 std::size_t slot, const std::vector<BufferResource>& buffers);
  std::size_t instances_per_run(const Stream& stream, std::size_t instances, std::size_t vertices,
                                const char* name) const;
  void set_instance_attributes(const FishDraw& draw, std::size_t slot);
  void point_instance_attributes(std::size_t first_instance) const;
  void bind_run(GLenum unit, const GlTexture& texture, GLint location, const Stream& stream,
                std::size_t first_instance, std::size_t instances) const;
};

}  // namespace finflex::render::detail

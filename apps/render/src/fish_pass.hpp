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
// A draw from a device list (FishDraw::list) is one glDrawElementsIndirect: its command
// and its entries (the id pass's instanced attribute, looked up in the ids uploaded as
// a table) are read where the GPU wrote them.
//
// Splitting: a buffer texture addresses at most GL_MAX_TEXTURE_BUFFER_SIZE texels
// (2^27 on Mesa and NVIDIA), four elements each where the stream is wide (5.4e8 floats:
// 16,000 instances of a 10,816-slot fish per attribute). Where glTexBufferRange exists, a draw goes
// in runs of instances whose elements fit one range; without it a draw must fit whole (else
// kGraphics).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gl_resources.hpp"
#include "render/fish_draw.hpp"
#include "shader_program.hpp"

namespace finflex::render::detail {

enum class FishOutput { kLitColour, kIds };

class FishPass {
 public:
  // `refraction`: the program that bends the view rays at the water surface
  // (Scene::view_refraction); the other keeps the straight rays' fewer varyings.
  FishPass(const GlLimits& limits, FishOutput output, bool refraction = false);
  // `fish` passed validate_fish(). Needs the scene framebuffer bound and the Scene
  // block at binding 0.
  void draw(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
            const std::vector<BufferResource>& buffers);

 private:
  // A stream as drawn: the GL buffer that holds it, its size, its layout.
  // Wide: read as four elements a texel (the buffer's whole texels hold every element
  // the draw reads), four times the elements a buffer texture addresses; only where
  // the draw would not fit one range otherwise.
  struct Stream {
    GLuint buffer = 0;
    std::size_t bytes = 0;
    StreamLayout layout;
    bool wide = false;
  };

  GlLimits limits_;
  FishOutput output_;
  ShaderProgram program_;
  GlTexture positions_;
  GlTexture normals_;
  GlTexture id_table_;             // a device list's FishDraw::ids, for the id pass
  std::vector<GlBuffer> uploads_;  // four per draw: positions, normals, transforms, ids
  GLint position_stream_ = -1;
  GLint normal_stream_ = -1;
  GLint positions_wide_ = -1;
  GLint normals_wide_ = -1;
  GLint albedo_ = -1;
  GLint patterned_ = -1;  // the colour pass only
  GLint ids_from_table_ = -1;
  GLuint transform_buffer_ = 0;  // this draw's uploads of instanced attributes; 0: none
  GLuint id_buffer_ = 0;
  std::size_t id_offset_ = 0;  // bytes: where id_buffer_'s values start

  GLuint upload(std::size_t slot, const void* data, std::size_t bytes);
  Stream prepare(const VertexStream& stream, std::size_t instances, std::size_t vertices,
                 std::size_t slot, const std::vector<BufferResource>& buffers);
  void widen_if_needed(Stream& stream, std::size_t instances, std::size_t vertices,
                       const char* name) const;
  std::size_t instances_per_run(const Stream& stream, std::size_t instances, std::size_t vertices,
                                const char* name) const;
  void set_instance_attributes(const FishDraw& draw, std::size_t slot,
                               const std::vector<BufferResource>& buffers);
  void draw_list(const FishDraw& draw, const std::string& field, const Stream& positions,
                 const Stream& normals, std::size_t run,
                 const std::vector<BufferResource>& buffers);
  void point_instance_attributes(std::size_t first_instance) const;
  void bind_run(GLenum unit, const GlTexture& texture, GLint location, GLint wide_location,
                const Stream& stream, std::size_t first_instance, std::size_t instances) const;
};

}  // namespace finflex::render::detail

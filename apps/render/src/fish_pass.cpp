#include "fish_pass.hpp"

#include <algorithm>
#include <climits>
#include <string>

#include "render/error.hpp"

namespace finflex::render::detail {

namespace {

// Instanced attributes: locations 0..3 the transform's columns, 4 the id (unsigned
// integer). Each is read from an upload, or is a constant: the identity, id 0.
constexpr GLuint kIdLocation = 4;

GLenum texel_format(ComponentType type) {
  return type == ComponentType::kFloat16 ? GL_R16F : GL_R32F;
}

// A stride in elements for the shader; 0 where it is never multiplied by more than 0
// (one instance per run, or one vertex) and would not fit a GLint.
GLint shader_stride(std::size_t bytes, std::size_t element, std::size_t count) {
  const std::size_t elements = bytes / element;
  if (count <= 1 || elements > static_cast<std::size_t>(INT_MAX)) return 0;
  return static_cast<GLint>(elements);
}

std::vector<std::string> fragment_files(FishOutput output) {
  if (output == FishOutput::kIds) return {"id.frag.glsl"};
  return {"scene_block.glsl", "shading.glsl", "surface.frag.glsl"};
}

}  // namespace

FishPass::FishPass(const GlLimits& limits, FishOutput output)
    : limits_(limits),
      output_(output),
      program_(output == FishOutput::kIds ? "fish ids" : "fish",
               {"scene_block.glsl", "fish.vert.glsl"}, fragment_files(output)),
      positions_(GlTexture::create()),
      normals_(GlTexture::create()) {
  program_.bind_block("Scene", 0);
  program_.bind_sampler("u_positions", 0);
  program_.bind_sampler("u_normals", 1);
  position_stream_ = program_.uniform("u_position_stream");
  normal_stream_ = program_.uniform("u_normal_stream");
  albedo_ = program_.uniform("u_albedo");
}

GLuint FishPass::upload(std::size_t slot, const void* data, std::size_t bytes) {
  while (uploads_.size() <= slot) uploads_.push_back(GlBuffer::create());
  glBindBuffer(GL_COPY_WRITE_BUFFER, uploads_[slot].get());
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_STREAM_DRAW);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  return uploads_[slot].get();
}

FishPass::Stream FishPass::prepare(const VertexStream& stream, std::size_t instances,
                                   std::size_t vertices, std::size_t slot,
                                   const std::vector<BufferResource>& buffers) {
  if (stream.host == nullptr) {
    const BufferResource& resource = buffers[stream.buffer];
    return {resource.buffer.get(), resource.bytes, stream.layout};
  }
  const std::size_t bytes = stream.layout.required_bytes(instances, vertices);
  return {upload(slot, stream.host, bytes), bytes, stream.layout};
}

std::size_t FishPass::instances_per_run(const Stream& stream, std::size_t instances,
                                        std::size_t vertices, const char* name) const {
  const StreamLayout& layout = stream.layout;
  const std::size_t element = layout.element_bytes();
  const std::size_t most = limits_.max_buffer_texels;
  if (!limits_.texture_buffer_range) {
    const std::size_t needed = layout.required_bytes(instances, vertices) / element;
    if (needed > most) {
      throw RenderError(
          ErrorCode::kGraphics, name,
          std::string(name) + ": " + std::to_string(needed) +
              " elements exceed GL_MAX_TEXTURE_BUFFER_SIZE (" + std::to_string(most) +
              ") and the driver has no glTexBufferRange: draw fewer instances at a time");
    }
    return instances;
  }
  // Elements of one instance from its first one, plus what aligning the range's start
  // down may add in front.
  const std::size_t one = layout.required_bytes(1, vertices) / element - layout.offset / element;
  const std::size_t slack = (limits_.buffer_offset_alignment + element - 1) / element;
  if (one + slack > most) {
    throw RenderError(ErrorCode::kGraphics, name,
                      std::string(name) + ": one instance spans " + std::to_string(one) +
                          " elements, more than GL_MAX_TEXTURE_BUFFER_SIZE (" +
                          std::to_string(most) + ")");
  }
  const std::size_t step = layout.instance_stride / element;
  if (step == 0) return instances;
  return std::min(instances, (most - one - slack) / step + 1);
}

void FishPass::bind_run(GLenum unit, const GlTexture& texture, GLint location, const Stream& stream,
                        std::size_t first_instance, std::size_t instances) const {
  const StreamLayout& layout = stream.layout;
  const std::size_t element = layout.element_bytes();
  const std::size_t start = layout.offset + first_instance * layout.instance_stride;
  std::size_t shift = start;  // bytes from the bound range's start to the run's first element
  glActiveTexture(unit);
  glBindTexture(GL_TEXTURE_BUFFER, texture.get());
  if (limits_.texture_buffer_range) {
    const std::size_t bound = start - start % limits_.buffer_offset_alignment;
    const std::size_t size = std::min(stream.bytes - bound, limits_.max_buffer_texels * element);
    glTexBufferRange(GL_TEXTURE_BUFFER, texel_format(layout.type), stream.buffer,
                     static_cast<GLintptr>(bound), static_cast<GLsizeiptr>(size));
    shift = start - bound;
  } else {
    glTexBuffer(GL_TEXTURE_BUFFER, texel_format(layout.type), stream.buffer);
  }
  glUniform4i(location, static_cast<GLint>(shift / element),
              shader_stride(layout.instance_stride, element, instances),
              shader_stride(layout.vertex_stride, element, 2),
              static_cast<GLint>(layout.component_stride / element));
}

void FishPass::draw(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
                    const std::vector<BufferResource>& buffers) {
  program_.use();
  for (std::size_t d = 0; d < fish.size(); ++d) {
    const FishDraw& draw = fish[d];
    if (draw.instance_count == 0) continue;
    const MeshResources& mesh = meshes[draw.mesh];
    const std::size_t count = draw.instance_count;
    const Stream positions = prepare(draw.positions, count, mesh.vertex_count, 4 * d, buffers);
    const Stream normals = prepare(draw.normals, count, mesh.vertex_count, 4 * d + 1, buffers);

    glBindVertexArray(mesh.vertex_array.get());
    set_instance_attributes(draw, 4 * d + 2);
    glUniform3f(albedo_, draw.albedo.r, draw.albedo.g, draw.albedo.b);

    const std::string field = "fish[" + std::to_string(d) + "]";
    const std::size_t run = std::min(
        instances_per_run(positions, count, mesh.vertex_count, (field + ".positions").c_str()),
        instances_per_run(normals, count, mesh.vertex_count, (field + ".normals").c_str()));
    for (std::size_t first = 0; first < count; first += run) {
      const std::size_t instances = std::min(run, count - first);
      bind_run(GL_TEXTURE0, positions_, position_stream_, positions, first, instances);
      bind_run(GL_TEXTURE1, normals_, normal_stream_, normals, first, instances);
      point_instance_attributes(first);
      glDrawElementsInstanced(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(instances));
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

void FishPass::set_instance_attributes(const FishDraw& draw, std::size_t slot) {
  const std::size_t count = draw.instance_count;
  transform_buffer_ = 0;
  id_buffer_ = 0;
  if (draw.transforms != nullptr) {
    transform_buffer_ = upload(slot, draw.transforms, count * sizeof(glm::mat4));
  }
  if (output_ == FishOutput::kIds) {
    id_buffer_ = upload(slot + 1, draw.ids, count * sizeof(std::uint32_t));
  }
  for (GLuint column = 0; column < 4; ++column) {
    if (transform_buffer_ != 0) {
      glEnableVertexAttribArray(column);
      glVertexAttribDivisor(column, 1);
    } else {  // the identity, as the attribute's constant value
      glDisableVertexAttribArray(column);
      const glm::vec4 identity = glm::mat4(1.0f)[static_cast<int>(column)];
      glVertexAttrib4f(column, identity.x, identity.y, identity.z, identity.w);
    }
  }
  if (id_buffer_ != 0) {
    glEnableVertexAttribArray(kIdLocation);
    glVertexAttribDivisor(kIdLocation, 1);
  } else {
    glDisableVertexAttribArray(kIdLocation);
    glVertexAttribI4ui(kIdLocation, 0, 0, 0, 0);
  }
}

void FishPass::point_instance_attributes(std::size_t first_instance) const {
  if (transform_buffer_ != 0) {
    glBindBuffer(GL_ARRAY_BUFFER, transform_buffer_);
    for (GLuint column = 0; column < 4; ++column) {
      const std::size_t offset = (first_instance * 4 + column) * sizeof(glm::vec4);
      glVertexAttribPointer(column, 4, GL_FLOAT, GL_FALSE, sizeof(glm::mat4),
                            reinterpret_cast<const void*>(offset));
    }
  }
  if (id_buffer_ != 0) {
    glBindBuffer(GL_ARRAY_BUFFER, id_buffer_);
    glVertexAttribIPointer(kIdLocation, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t),
                           reinterpret_cast<const void*>(first_instance * sizeof(std::uint32_t)));
  }
}

}  // namespace finflex::render::detail

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

GLenum texel_format(ComponentType type, bool wide) {
  if (type == ComponentType::kFloat16) return wide ? GL_RGBA16F : GL_R16F;
  return wide ? GL_RGBA32F : GL_R32F;
}

constexpr std::size_t kWideElements = 4;  // a wide texel's elements

// A stride in elements for the shader; 0 where it is never multiplied by more than 0
// (one instance per run, or one vertex) and would not fit a GLint.
GLint shader_stride(std::size_t bytes, std::size_t element, std::size_t count) {
  const std::size_t elements = bytes / element;
  if (count <= 1 || elements > static_cast<std::size_t>(INT_MAX)) return 0;
  return static_cast<GLint>(elements);
}

std::vector<std::string> fragment_files(FishOutput output) {
  if (output == FishOutput::kIds) return {"id.frag.glsl"};
  return {"scene_block.glsl", "shading.glsl", "surface_inputs.glsl", "fish.frag.glsl"};
}

}  // namespace

FishPass::FishPass(const GlLimits& limits, FishOutput output, bool refraction)
    : limits_(limits),
      output_(output),
      program_(output == FishOutput::kIds ? "fish ids" : "fish",
               {"scene_block.glsl", "refraction.glsl", "fish.vert.glsl"}, fragment_files(output),
               refraction_defines(refraction)),
      positions_(GlTexture::create()),
      normals_(GlTexture::create()),
      id_table_(GlTexture::create()) {
  program_.bind_block("Scene", 0);
  program_.bind_sampler("u_positions", 0);
  program_.bind_sampler("u_normals", 1);
  program_.bind_sampler("u_id_table", 2);
  ids_from_table_ = program_.uniform("u_ids_from_table");
  position_stream_ = program_.uniform("u_position_stream");
  normal_stream_ = program_.uniform("u_normal_stream");
  positions_wide_ = program_.uniform("u_positions_wide");
  normals_wide_ = program_.uniform("u_normals_wide");
  albedo_ = program_.uniform("u_albedo");
  if (output == FishOutput::kLitColour) patterned_ = program_.uniform("u_patterned");
}

// Uploads are padded to whole 16-byte texels (the padding is never read).
GLuint FishPass::upload(std::size_t slot, const void* data, std::size_t bytes) {
  while (uploads_.size() <= slot) uploads_.push_back(GlBuffer::create());
  glBindBuffer(GL_COPY_WRITE_BUFFER, uploads_[slot].get());
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>((bytes + 15) / 16 * 16), nullptr,
               GL_STREAM_DRAW);
  glBufferSubData(GL_COPY_WRITE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  return uploads_[slot].get();
}

FishPass::Stream FishPass::prepare(const VertexStream& stream, std::size_t instances,
                                   std::size_t vertices, std::size_t slot,
                                   const std::vector<BufferResource>& buffers) {
  Stream out;
  out.layout = stream.layout;
  const std::size_t needed = stream.layout.required_bytes(instances, vertices);
  if (stream.host == nullptr) {
    const BufferResource& resource = buffers[stream.buffer];
    out.buffer = resource.buffer.get();
    out.bytes = resource.bytes;
  } else {
    out.buffer = upload(slot, stream.host, needed);
    out.bytes = (needed + 15) / 16 * 16;
  }
  return out;
}

// Wide where one texel an element would not hold the draw in one range (each element
// fetch then reads a whole texel: four times the texture traffic, measured 10 % of the
// draw), and whole texels hold every element read.
void FishPass::widen_if_needed(Stream& stream, std::size_t instances, std::size_t vertices,
                               const char* name) const {
  const std::size_t texel = kWideElements * stream.layout.element_bytes();
  const std::size_t needed = stream.layout.required_bytes(instances, vertices);
  if (stream.bytes / texel * texel < needed) return;
  if (!limits_.texture_buffer_range) {
    stream.wide = needed / stream.layout.element_bytes() > limits_.max_buffer_texels;
    return;
  }
  try {
    stream.wide = instances_per_run(stream, instances, vertices, name) < instances;
  } catch (const RenderError&) {
    stream.wide = true;  // not one instance fits a narrow range
  }
}

std::size_t FishPass::instances_per_run(const Stream& stream, std::size_t instances,
                                        std::size_t vertices, const char* name) const {
  const StreamLayout& layout = stream.layout;
  const std::size_t element = layout.element_bytes();
  // Elements one texture addresses (a wide range may lose up to a texel at its end).
  const std::size_t most = stream.wide ? limits_.max_buffer_texels * kWideElements - kWideElements
                                       : limits_.max_buffer_texels;
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
  const std::size_t texel = stream.wide ? kWideElements * element : element;
  const std::size_t slack =
      (std::max(limits_.buffer_offset_alignment, texel) + element - 1) / element;
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

void FishPass::bind_run(GLenum unit, const GlTexture& texture, GLint location, GLint wide_location,
                        const Stream& stream, std::size_t first_instance,
                        std::size_t instances) const {
  const StreamLayout& layout = stream.layout;
  const std::size_t element = layout.element_bytes();
  const std::size_t texel = stream.wide ? kWideElements * element : element;
  const std::size_t start = layout.offset + first_instance * layout.instance_stride;
  std::size_t shift = start;  // bytes from the bound range's start to the run's first element
  glActiveTexture(unit);
  glBindTexture(GL_TEXTURE_BUFFER, texture.get());
  const GLenum format = texel_format(layout.type, stream.wide);
  if (limits_.texture_buffer_range) {
    const std::size_t alignment = std::max(limits_.buffer_offset_alignment, texel);
    const std::size_t bound = start - start % alignment;
    const std::size_t size =
        std::min(stream.bytes - bound, limits_.max_buffer_texels * texel) / texel * texel;
    glTexBufferRange(GL_TEXTURE_BUFFER, format, stream.buffer, static_cast<GLintptr>(bound),
                     static_cast<GLsizeiptr>(size));
    shift = start - bound;
  } else {
    glTexBuffer(GL_TEXTURE_BUFFER, format, stream.buffer);
  }
  glUniform1i(wide_location, stream.wide ? 1 : 0);
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
    Stream positions = prepare(draw.positions, count, mesh.vertex_count, 4 * d, buffers);
    Stream normals = prepare(draw.normals, count, mesh.vertex_count, 4 * d + 1, buffers);

    glBindVertexArray(mesh.vertex_array.get());
    set_instance_attributes(draw, 4 * d + 2, buffers);
    glUniform3f(albedo_, draw.albedo.r, draw.albedo.g, draw.albedo.b);
    if (output_ == FishOutput::kLitColour) glUniform1i(patterned_, mesh.patterned ? 1 : 0);

    const std::string field = "fish[" + std::to_string(d) + "]";
    widen_if_needed(positions, count, mesh.vertex_count, (field + ".positions").c_str());
    widen_if_needed(normals, count, mesh.vertex_count, (field + ".normals").c_str());
    const std::size_t run = std::min(
        instances_per_run(positions, count, mesh.vertex_count, (field + ".positions").c_str()),
        instances_per_run(normals, count, mesh.vertex_count, (field + ".normals").c_str()));
    if (draw.list.buffer != kNoBuffer) {
      draw_list(draw, field, positions, normals, run, buffers);
      continue;
    }
    for (std::size_t first = 0; first < count; first += run) {
      const std::size_t instances = std::min(run, count - first);
      bind_run(GL_TEXTURE0, positions_, position_stream_, positions_wide_, positions, first,
               instances);
      bind_run(GL_TEXTURE1, normals_, normal_stream_, normals_wide_, normals, first, instances);
      point_instance_attributes(first);
      glDrawElementsInstanced(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(instances));
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

// One indirect draw: the GPU's command and entries, every row in one buffer range.
void FishPass::draw_list(const FishDraw& draw, const std::string& field, const Stream& positions,
                         const Stream& normals, std::size_t run,
                         const std::vector<BufferResource>& buffers) {
  const std::size_t count = draw.instance_count;
  if (run < count) {
    throw RenderError(ErrorCode::kGraphics, field + ".list",
                      field + ".list: " + std::to_string(count) +
                          " rows need more than one buffer texture (GL_MAX_TEXTURE_BUFFER_SIZE "
                          "allows " +
                          std::to_string(run) + "): give the list fewer rows");
  }
  bind_run(GL_TEXTURE0, positions_, position_stream_, positions_wide_, positions, 0, count);
  bind_run(GL_TEXTURE1, normals_, normal_stream_, normals_wide_, normals, 0, count);
  point_instance_attributes(0);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffers[draw.list.buffer].buffer.get());
  glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                         reinterpret_cast<const void*>(draw.list.command_offset));
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void FishPass::set_instance_attributes(const FishDraw& draw, std::size_t slot,
                                       const std::vector<BufferResource>& buffers) {
  const std::size_t count = draw.instance_count;
  const bool listed = draw.list.buffer != kNoBuffer;
  transform_buffer_ = 0;
  id_buffer_ = 0;
  id_offset_ = 0;
  if (draw.transforms != nullptr) {
    transform_buffer_ = upload(slot, draw.transforms, count * sizeof(glm::mat4));
  }
  // The id pass needs the ids (fish_validation); the colour pass shades by them where
  // the draw has them.
  const bool ids = draw.ids != nullptr;
  glUniform1i(ids_from_table_, listed && ids ? 1 : 0);
  if (listed && ids) {
    // The entries stay where the GPU wrote them; the table they index is uploaded.
    id_buffer_ = buffers[draw.list.buffer].buffer.get();
    id_offset_ = draw.list.entries_offset;
    const GLuint table = upload(slot + 1, draw.ids, draw.id_count * sizeof(std::uint32_t));
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_BUFFER, id_table_.get());
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32UI, table);
  } else if (ids) {
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
    glVertexAttribIPointer(
        kIdLocation, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t),
        reinterpret_cast<const void*>(id_offset_ + first_instance * sizeof(std::uint32_t)));
  }
}

}  // namespace finflex::render::detail

#include "tank_pass.hpp"

#include <cstddef>

#include "tank_mesh.hpp"

namespace finflex::render::detail {

namespace {

bool same_tank(const Tank& a, const Tank& b) {
  return a.radius == b.radius && a.wall_height == b.wall_height && a.water_depth == b.water_depth &&
         a.wall_albedo == b.wall_albedo && a.floor_albedo == b.floor_albedo &&
         a.segments == b.segments;
}

}  // namespace

TankPass::TankPass(bool refraction)
    : program_("tank", {"scene_block.glsl", "refraction.glsl", "tank.vert.glsl"},
               {"scene_block.glsl", "shading.glsl", "surface_inputs.glsl", "surface.frag.glsl"},
               refraction_defines(refraction)),
      vertex_array_(GlVertexArray::create()),
      vertices_(GlBuffer::create()),
      indices_(GlBuffer::create()) {
  program_.bind_block("Scene", 0);
  glBindVertexArray(vertex_array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  const auto stride = static_cast<GLsizei>(sizeof(TankVertex));
  const auto attribute = [&](GLuint location, std::size_t offset) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offset));
  };
  attribute(0, offsetof(TankVertex, position));
  attribute(1, offsetof(TankVertex, normal));
  attribute(2, offsetof(TankVertex, albedo));
  glBindVertexArray(0);
}

void TankPass::rebuild(const Tank& tank) {
  const TankMesh mesh = make_tank_mesh(tank);
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(TankVertex)),
               mesh.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(vertex_array_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  index_count_ = static_cast<GLsizei>(mesh.indices.size());
  built_for_ = tank;
}

void TankPass::draw(const Tank& tank, const TankRows& rows) {
  if (!built_for_ || !same_tank(*built_for_, tank)) rebuild(tank);
  program_.use();
  glBindVertexArray(vertex_array_.get());
  glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, rows.count);
  glBindVertexArray(0);
}

}  // namespace finflex::render::detail

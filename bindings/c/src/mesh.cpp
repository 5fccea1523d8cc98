// Meshes: files, arrays, body frames.
#include <cstring>

#include "handles.hpp"

namespace {

using finflex::Error;
using finflex::ErrorCode;

// Throws unless `count` is exactly `items` x `per_item` values.
void check_count(std::size_t count, std::size_t items, std::size_t per_item, const char* what) {
  if (count != items * per_item) {
    throw Error(ErrorCode::kInvalidArgument, "count",
                "count = " + std::to_string(count) + ": expected " +
                    std::to_string(items * per_item) + " values (" + std::to_string(items) + " " +
                    what + " x " + std::to_string(per_item) + ")");
  }
}

// Copies `items` items of three values each from `source` to the caller's `out` of
// `count` values.
template <typename Value>
void copy_out(const Value* source, std::size_t items, Value* out, std::size_t count,
              const char* field, const char* what) {
  finflex::c::require(out, field);
  check_count(count, items, 3, what);
  if (count > 0) std::memcpy(out, source, count * sizeof(Value));
}

void to_c(const finflex::BodyFrame& frame, finflex_body_frame* out) {
  for (int c = 0; c < 3; ++c) {
    out->origin[c] = frame.origin[c];
    out->axis_x[c] = frame.axis_x[c];
    out->axis_y[c] = frame.axis_y[c];
    out->axis_z[c] = frame.axis_z[c];
  }
  out->length = frame.length;
}

}  // namespace

using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

extern "C" {

finflex_status finflex_mesh_load(const char* path, finflex_mesh** mesh) {
  return finflex::c::create(nullptr, mesh, "mesh", [&] {
    auto handle = std::make_unique<finflex_mesh>();
    handle->mesh = finflex::load_mesh(require(path, "path"));
    return handle;
  });
}

finflex_status finflex_mesh_create(const float* positions, size_t vertex_count,
                                   const uint32_t* indices, size_t index_count,
                                   const float* normals, finflex_mesh** mesh) {
  return finflex::c::create(nullptr, mesh, "mesh", [&] {
    if (vertex_count > 0) require(positions, "positions");
    if (index_count > 0) require(indices, "indices");
    auto handle = std::make_unique<finflex_mesh>();
    finflex::Mesh& m = handle->mesh;
    m.positions.resize(vertex_count);
    if (vertex_count > 0) std::memcpy(m.positions.data(), positions, vertex_count * 12);
    m.indices.assign(indices, indices + index_count);
    if (normals != nullptr) {
      m.normals.resize(vertex_count);
      if (vertex_count > 0) std::memcpy(m.normals.data(), normals, vertex_count * 12);
    } else {
      finflex::compute_vertex_normals(m);
    }
    finflex::validate_mesh(m);
    return handle;
  });
}

void finflex_mesh_destroy(finflex_mesh* mesh) { delete mesh; }

const finflex_error* finflex_mesh_error(const finflex_mesh* mesh) { return slot_of(mesh); }

finflex_status finflex_mesh_save(finflex_mesh* mesh, const char* path) {
  return guarded(slot_of(mesh),
                 [&] { finflex::save_mesh(require(path, "path"), require(mesh, "mesh")->mesh); });
}

size_t finflex_mesh_vertex_count(const finflex_mesh* mesh) {
  return mesh == nullptr ? 0 : mesh->mesh.vertex_count();
}

size_t finflex_mesh_triangle_count(const finflex_mesh* mesh) {
  return mesh == nullptr ? 0 : mesh->mesh.triangle_count();
}

finflex_status finflex_mesh_get_positions(finflex_mesh* mesh, float* positions, size_t count) {
  return guarded(slot_of(mesh), [&] {
    const finflex::Mesh& m = require(mesh, "mesh")->mesh;
    copy_out(reinterpret_cast<const float*>(m.positions.data()), m.vertex_count(), positions, count,
             "positions", "vertices");
  });
}

finflex_status finflex_mesh_get_normals(finflex_mesh* mesh, float* normals, size_t count) {
  return guarded(slot_of(mesh), [&] {
    const finflex::Mesh& m = require(mesh, "mesh")->mesh;
    copy_out(reinterpret_cast<const float*>(m.normals.data()), m.vertex_count(), normals, count,
             "normals", "vertices");
  });
}

finflex_status finflex_mesh_get_indices(finflex_mesh* mesh, uint32_t* indices, size_t count) {
  return guarded(slot_of(mesh), [&] {
    const finflex::Mesh& m = require(mesh, "mesh")->mesh;
    copy_out(m.indices.data(), m.triangle_count(), indices, count, "indices", "triangles");
  });
}

finflex_status finflex_mesh_find_body_frame(finflex_mesh* mesh, finflex_body_frame* frame) {
  return guarded(slot_of(mesh), [&] {
    const finflex::BodyFrame found = finflex::find_body_frame(require(mesh, "mesh")->mesh);
    to_c(found, require(frame, "frame"));
  });
}

void finflex_body_frame_identity(finflex_body_frame* frame) {
  if (frame != nullptr) to_c(finflex::BodyFrame::identity(), frame);
}

}  // extern "C"

#include "finflex/subdivide.hpp"

#include <string>
#include <vector>

// OpenMesh's templates trip GCC's -Wmaybe-uninitialized (and its own sign and
// shadowing habits) when instantiated here; they are not ours to fix.
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wconversion"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include "finflex/error.hpp"

namespace finflex {
namespace {

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

}  // namespace

Mesh subdivide_loop(const Mesh& mesh, int levels) {
  if (levels < 0 || levels > 8) {
    throw Error(ErrorCode::kInvalidArgument, "levels",
                "levels = " + std::to_string(levels) + " is outside [0, 8]");
  }
  validate_mesh(mesh);
  if (mesh.triangle_count() == 0) {
    throw Error(ErrorCode::kInvalidMesh, "indices", "the mesh has no triangles to subdivide");
  }
  TriMesh tri;
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(mesh.vertex_count());
  for (const glm::vec3& p : mesh.positions) handles.push_back(tri.add_vertex({p.x, p.y, p.z}));
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    tri.add_face(handles[mesh.indices[3 * t]], handles[mesh.indices[3 * t + 1]],
                 handles[mesh.indices[3 * t + 2]]);
  }
  if (levels > 0) {
    OpenMesh::Subdivider::Uniform::LoopT<TriMesh> loop;
    loop.attach(tri);
    loop(static_cast<std::size_t>(levels));
    loop.detach();
  }
  Mesh out;
  out.positions.reserve(tri.n_vertices());
  for (const auto& v : tri.vertices()) {
    const auto& p = tri.point(v);
    out.positions.emplace_back(p[0], p[1], p[2]);
  }
  out.indices.reserve(3 * tri.n_faces());
  for (const auto& f : tri.faces()) {
    for (const auto& v : tri.fv_range(f))
      out.indices.push_back(static_cast<std::uint32_t>(v.idx()));
  }
  compute_vertex_normals(out);
  return out;
}

}  // namespace finflex

#pragma GCC diagnostic pop

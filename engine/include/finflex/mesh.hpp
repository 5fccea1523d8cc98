// Host-side triangle mesh: the rest shape FinFlex deforms, and the form deformed
// instances take when handed back as whole meshes (e.g. to write a file).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/export.hpp"

namespace finflex {

// A named run of consecutive triangles: an OBJ group ("g name"), or a glTF mesh
// primitive ("mesh name/primitive index"). Rig selectors pick components by name.
struct FaceGroup {
  std::string name;
  std::size_t first_triangle = 0;
  std::size_t triangle_count = 0;
};

// Vertex attributes are parallel arrays of length vertex_count(); optional ones are
// empty when absent. Faces are triangles, three indices each, counter-clockwise seen
// from outside (the side the normals point to).
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // unit length; empty: compute_vertex_normals() fills it
  std::vector<glm::vec4> tangents;   // optional: xyz unit tangent, w = +-1 bitangent sign
  std::vector<glm::vec2> texcoords;  // optional: passed through unchanged
  std::vector<std::uint32_t> indices;
  std::vector<FaceGroup> groups;  // optional: empty when the file names none

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  bool has_normals() const { return !normals.empty(); }
  bool has_tangents() const { return !tangents.empty(); }
};

// Throws finflex::Error (kInvalidMesh) naming the first bad field and value: no
// vertices, attribute arrays of the wrong length, index count not a multiple of 3,
// an index out of range, a non-finite position/normal/tangent/texcoord, a zero normal.
// The checks run in that order; the field is e.g. "normals", "indices[7]",
// "positions[12].y", and the message repeats it with the value.
// A mesh without triangles (indices empty) is valid.
FINFLEX_API void validate_mesh(const Mesh& mesh);

// Area-weighted vertex normals from the triangles (overwrites mesh.normals).
// A vertex used by no triangle, or only by zero-area ones, gets the normal (0, 0, 1).
// Throws kInvalidMesh if the index count is not a multiple of 3 or an index is out
// of range; the other attributes are not checked.
FINFLEX_API void compute_vertex_normals(Mesh& mesh);

// Per-triangle unit normals (right-hand rule on the index order), for tests and tools.
// A zero-area triangle gets (0, 0, 0). Throws kInvalidMesh like compute_vertex_normals.
FINFLEX_API std::vector<glm::dvec3> face_normals(const std::vector<glm::vec3>& positions,
                                                 const std::vector<std::uint32_t>& indices);

}  // namespace finflex

// Reading and writing meshes. Formats follow the file extension (case-insensitive):
// .obj .ply .off .stl through OpenMesh, .gltf .glb through tinygltf.
#pragma once

#include <string>

#include "finflex/export.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

// Loads a triangle mesh. Polygons are fan-triangulated around their first corner,
// in file order. glTF: the default scene (else scene 0, else every root node) is
// flattened depth-first: node transforms are applied to positions, normals (inverse
// transpose) and tangents (and a mirroring transform flips the winding and the
// tangents' w); TRIANGLES primitives are concatenated in traversal order, any other
// mode is a kFormat error naming the mesh and primitive; POSITION, NORMAL, TANGENT and
// TEXCOORD_0 are read; image files that are missing do not stop the load.
// Vertex count and order are those of the file. Exception: STL has no shared
// vertices, so one vertex is made per distinct position, in order of first use.
// Normals are normalized; per-corner normals (OBJ "vn") are averaged per vertex;
// vertices without a file normal get area-weighted normals. A vertex with several
// texcoords (OBJ texture seams) keeps the first one in file order.
// The result passes validate_mesh(). Errors (the message starts with the quoted
// path): kIo (missing, unreadable, a directory; a glTF buffer file that cannot be
// read), kFormat (unsupported extension, empty file, content that is not a mesh of
// the format), kInvalidMesh (e.g. an index out of range, a NaN coordinate; the field
// names it). Thread-safe; OpenMesh formats are read one at a time.
FINFLEX_API Mesh load_mesh(const std::string& path);

// Writes `mesh` (validated first, before any file is touched) with its normals
// (computed if it has none), and tangents and texcoords where the format carries
// them: glTF/GLB: all (one mesh, one primitive, one node, u32 indices; a .gltf holds
// its buffer as a base64 data URI); OBJ, PLY, OFF: normals and texcoords; STL: facet
// normals only. PLY and STL are binary; all formats keep float positions exactly.
// The file is written to a temporary name in the same folder and renamed into place:
// on any error the temporary file is removed and `path` is neither created nor
// changed. Errors: kFormat (unsupported extension), kInvalidMesh (validation; glTF
// also needs at least one triangle), kIo (missing folder, `path` is a directory,
// write failure).
FINFLEX_API void save_mesh(const std::string& path, const Mesh& mesh);

}  // namespace finflex

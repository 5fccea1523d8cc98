// Reading and writing meshes. Formats follow the file extension (case-insensitive):
// .obj .ply .off .stl through OpenMesh, .gltf .glb through tinygltf.
#pragma once

#include <string>

#include "finflex/mesh.hpp"

namespace finflex {

// Loads a triangle mesh. Polygons are fan-triangulated. glTF: the default scene is
// flattened (node transforms applied to positions, normals and tangents; primitives
// of mode TRIANGLES concatenated in traversal order); POSITION, NORMAL, TANGENT and
// TEXCOORD_0 are read; image files that are missing do not stop the load.
// Vertex count and order are those of the file (OpenMesh is asked to keep them).
// A mesh without normals gets area-weighted normals computed. The result passes
// validate_mesh(). Errors: kIo (cannot read), kFormat (unsupported extension or
// content), kInvalidMesh.
Mesh load_mesh(const std::string& path);

// Writes `mesh` (validated first) with its normals, and tangents and texcoords where
// the format carries them (glTF: all; PLY/OBJ: normals and texcoords; OFF/STL:
// normals only where the format allows). The file is written to a temporary name in
// the same folder and renamed into place: on any error `path` is left untouched.
void save_mesh(const std::string& path, const Mesh& mesh);

}  // namespace finflex

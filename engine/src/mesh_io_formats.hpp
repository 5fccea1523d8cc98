// Private: the per-format readers and writers behind load_mesh / save_mesh.
//
// Division of labour: mesh_io.cpp picks the format from the extension, checks that
// the input file exists and is readable, validates meshes, computes missing normals,
// prefixes error messages with the path and does the atomic temp-file + rename
// write. The functions here only translate between bytes and a Mesh:
// - readers take the path of an existing, non-empty, readable file and return the
//   mesh as found in the file (normals may be empty; nothing is validated yet);
//   they throw finflex::Error (kFormat for content they cannot use, kIo for a file
//   they reference that cannot be read, kInvalidMesh for inconsistent data);
// - writers take a mesh that passed validate_mesh() and has normals, and write it
//   to an open binary stream; they throw finflex::Error and leave stream failures
//   (disk full, ...) to the caller, who checks the stream.
#pragma once

#include <ostream>
#include <string>

#include "finflex/mesh.hpp"

namespace finflex::io {

enum class MeshFormat { kObj, kPly, kOff, kStl, kGltf, kGlb };

// OBJ, PLY, OFF, STL through OpenMesh (mesh_io_openmesh.cpp).
Mesh read_openmesh(const std::string& path, MeshFormat format);
void write_openmesh(std::ostream& out, MeshFormat format, const Mesh& mesh);

// glTF 2.0 (.gltf) and GLB (.glb) through tinygltf (mesh_io_gltf.cpp).
Mesh read_gltf(const std::string& path, MeshFormat format);
void write_gltf(std::ostream& out, MeshFormat format, const Mesh& mesh);

}  // namespace finflex::io

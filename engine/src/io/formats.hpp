// Private: the per-format readers and writers behind load_mesh / save_mesh.
//
// Division of labour: mesh_io.cpp picks the format from the extension, reads the
// input file (regular files only, mesh_io_file.cpp), prefixes error messages with
// the path and does the atomic temp-file + rename write. read_mesh_bytes() turns the
// bytes into a validated Mesh through the functions below, which only translate
// between bytes and a Mesh:
// - readers take the whole file in memory and return the mesh as found in it
//   (normals may be empty; nothing is validated yet). They never trust a count
//   declared in the file before checking it against the bytes that follow, never
//   recurse on input-controlled depth, and throw finflex::Error: kFormat for content
//   they cannot use, kInvalidMesh for readable but invalid data (non-finite or
//   out-of-range numbers, indices out of range, repeated polygon corners), kIo for a
//   file the input references that cannot be read. The field and the message name
//   the place (text: "line 12"; binary and glTF: the element) and the value;
// - writers take a mesh that passed validate_mesh() and has normals, and write it
//   to an open binary stream; they throw finflex::Error and leave stream failures
//   (disk full, ...) to the caller, who checks the stream.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "finflex/mesh.hpp"

namespace finflex::io {

enum class MeshFormat { kObj, kPly, kOff, kStl, kGltf, kGlb };

const char* format_name(MeshFormat format);

// Throws kIo (reason only, no path) unless `path` names a regular file (symbolic
// links followed). Looks at the file's type only; opens nothing.
void require_regular_file(const std::string& path);

// The whole content of `path` if it is a regular file (symbolic links followed).
// Anything else (directory, FIFO, socket, device) is refused without being opened,
// so nothing blocks and nothing endless is read. Throws kIo with the reason only
// (no path): "does not exist", "is a directory, not a regular file", ...
std::string read_regular_file(const std::string& path);

// read_regular_file for a file that may have at most `max_bytes` bytes: beyond, kIo
// "has N bytes, more than the <max_bytes> <limit>", before reading.
std::vector<unsigned char> read_regular_file_bytes(const std::string& path, std::uint64_t max_bytes,
                                                   const char* limit);

// The mesh in `bytes` (the content of a `format` file), with normals (computed when
// the file has none) and validated (validate_mesh). `base_dir` is the folder that
// relative glTF URIs resolve against ("" for none). Throws finflex::Error (messages
// do not name the file); the in-memory entry point of load_mesh and the fuzzers.
Mesh read_mesh_bytes(std::string_view bytes, MeshFormat format, const std::string& base_dir);

// Strict readers of our own (mesh_io_obj.cpp, mesh_io_off.cpp, mesh_io_ply.cpp,
// mesh_io_stl.cpp): vertices in file order, polygons fan-triangulated in file order.
Mesh read_obj(std::string_view text);
Mesh read_off(std::string_view text);
Mesh read_ply(std::string_view bytes);
Mesh read_stl(std::string_view bytes);

// glTF 2.0 (.gltf) and GLB (.glb) through tinygltf (mesh_io_gltf*.cpp). The content
// decides between the two, not the extension.
Mesh read_gltf(std::string_view bytes, const std::string& base_dir);

// OBJ, PLY, OFF, STL through OpenMesh's writers (mesh_io_openmesh.cpp).
void write_openmesh(std::ostream& out, MeshFormat format, const Mesh& mesh);

// glTF / GLB through tinygltf (mesh_io_gltf_write.cpp).
void write_gltf(std::ostream& out, MeshFormat format, const Mesh& mesh);

}  // namespace finflex::io

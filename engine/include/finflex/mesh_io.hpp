// Reading and writing meshes. Formats follow the file extension (case-insensitive):
// .obj .ply .off .stl (strict readers of FinFlex's own, OpenMesh's writers), .gltf
// .glb through tinygltf.
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
// Vertex count and order are those of the file, and every polygon of the file is in
// the result: a file is read whole or not at all. Exception: STL has no shared
// vertices, so one vertex is made per distinct position, in order of first use.
// Normals are normalized; per-corner normals (OBJ "vn") are averaged per vertex;
// vertices without a file normal get area-weighted normals. A vertex with several
// texcoords (OBJ texture seams) keeps the first one in file order.
//
// What the formats accept (docs/reliability.md: the tests, fuzzing and limits):
// - OBJ: v (x y z, optionally w or r g b, checked and dropped), vt, vn, f with v,
//   v/vt, v//vn, v/vt/vn corners and negative (relative) indices, g and o (groups);
//   s, usemtl, mtllib, l, p, vp and display attributes are ignored; any other
//   statement, free-form geometry and '\' line continuations are kFormat errors.
// - OFF: ASCII [ST][C][N]OFF (nOFF with dimension 3); binary OFF is not read.
// - PLY: ascii, binary_little_endian, binary_big_endian 1.0; vertex x y z, nx ny nz,
//   a texcoord pair (u v, s t, texture_u texture_v, texture_s texture_t); face
//   vertex_indices (or vertex_index); other properties and elements are checked and
//   dropped (triangle strips, element "tristrips", are a kFormat error).
// - STL: binary when the file size is exactly 84 + 50 * the triangle count, else
//   ASCII ("solid" ... "endsolid", several solids allowed); facet normals dropped.
// - glTF / GLB: GLB header and chunk lengths must match the file; JSON arrays and
//   objects may nest at most 64 levels (extras included); URIs are read only when
//   they name regular files (a buffer URI naming a folder is a kIo error saying so),
//   and no more bytes than the buffers declare (byteLength) in all.
//   The node hierarchy must be a forest (a node listed twice, a node with two
//   parents, a cycle, or a scene node that is not a root is a kFormat error naming
//   the node), at most 1024 levels deep; a node placing a mesh needs a finite,
//   invertible transform. An accessor without bufferView (zeros) may not have more
//   elements than the input has bytes, and the flattened scene may hold at most 4
//   vertices, indices and group-name bytes per byte of input (the file and its
//   buffers), however often nodes instance a mesh.
// Every number must be all of its token (no hexadecimal, no trailing characters);
// kept values must be finite and within the float range (underflow rounds to 0); a
// polygon needs at least 3 distinct, existing vertices (STL triangles excepted);
// element counts declared in a header are checked against the bytes that follow
// before anything is allocated.
//
// The result passes validate_mesh(). Errors (the message starts with the quoted
// path, then names the line ("line 12") or the element ("vertex[3].y",
// "triangles[5]") and the value): kIo (missing or unreadable file; not a regular
// file: a directory, FIFO, socket or device is refused at once, without being
// opened; a glTF buffer file that cannot be read), kFormat (unsupported extension,
// empty file, content that is not a mesh of the format: unreadable numbers, unknown
// statements, counts beyond the file's size, a polygon with fewer than 3 corners),
// kInvalidMesh (readable but invalid data: a non-finite or out-of-range number, an
// index out of range, a polygon using a vertex twice; the field names it).
// Thread-safe.
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

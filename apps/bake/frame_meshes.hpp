// The swim cycle as one mesh file per frame (<stem>_frame_000.obj ...), for tools that
// import a sequence of meshes (Blender's mesh sequence cache, Houdini, Alembic
// converters): every file has the mesh's vertex order, faces and texture coordinates,
// with the frame's positions and normals, in metres (y up, head towards +z).
#pragma once

#include <string>

#include "finflex/mesh.hpp"
#include "swim_cycle.hpp"

namespace finflex::bake {

// `extension`: "obj", "ply", "off", "stl", "gltf" or "glb" (finflex::save_mesh).
// finflex::Error kIo / kFormat.
void write_frame_meshes(const std::string& folder, const std::string& stem,
                        const std::string& extension, const Mesh& mesh, const BakedCycle& baked);

}  // namespace finflex::bake

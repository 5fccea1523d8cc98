// The swim cycle as glTF 2.0 morph-target animation, which standard players (three.js,
// Babylon.js, Blender, Unity's glTFast, Godot, the Khronos sample viewer) play:
//
//   the mesh:      the rest pose (straight fish) with its normals (and texture
//                  coordinates when the mesh has them);
//   morph targets: one per frame k, POSITION and NORMAL displacements from the rest
//                  pose to frame k (extras.targetNames "frame_000" ...);
//   animation:     "swim", the mesh's weights, LINEAR, keys at t_k = k T / N for
//                  k = 0 .. N: at t_k weight k is 1 and the others 0 (key N is key 0
//                  again, so the loop closes); between keys the shape blends linearly
//                  from frame k to frame k + 1.
//
// Memory and file size: 24 bytes per vertex and frame (12 of positions, 12 of normals).
#pragma once

#include <string>

#include "finflex/mesh.hpp"
#include "swim_cycle.hpp"

namespace finflex::bake {

// Writes `baked` (of `mesh`, in mesh vertex order) as a .glb. finflex::Error kIo.
void write_morph_animation(const std::string& path, const std::string& name, const Mesh& mesh,
                           const BakedCycle& baked);

}  // namespace finflex::bake

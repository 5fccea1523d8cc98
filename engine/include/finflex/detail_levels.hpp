// Levels of detail of a rigged mesh: coarser meshes of the same fish, made by
// meshoptimizer's edge-collapse simplifier, each with the full mesh's rig carried over.
//
//   RiggedMesh fish(mesh, resolve_rig(load_rig_file("data/rigs/blub_swim.rig.json"), mesh));
//   DetailLevels levels = make_detail_levels(fish, LevelOptions{});
//   levels.level(0).model   // every vertex (reordered), every triangle
//   levels.level(3).model   // the first levels.level(3).vertex_count vertices, fewer triangles
//
// The contract:
// - One vertex order for all levels: level k uses the first vertex_count(k) vertices of
//   level 0, and vertex_count falls with k (a coarser level's vertices are a prefix of
//   every finer level's). Level 0 is the input with its vertices in that order (every
//   vertex, every triangle); full_vertex_of maps them back to the input's.
// - The rig is the input's: the same components, stages, frames and stage geometry,
//   each component's vertex list cut to the level's vertices. So a vertex a level keeps
//   is deformed exactly as the full mesh deforms it (the same stages, the same
//   parameters), and the levels can be switched between frames without a jump.
// - Triangles are simplified within one component at a time, with the component's
//   border (its seam with other components, and the mesh's own open edges) locked and
//   triangles across components kept: a fin stays a fin, attached where it was.
// - Each level's geometric_error, in mesh units: how far its surface is from the full
//   mesh's, the larger of meshoptimizer's error of each step of the cascade (as a
//   distance, summed) and the two-sided distance measured between the two surfaces
//   (from every vertex of each, and the middle and edge midpoints of each of the
//   level's triangles, to the other's nearest point); never below a finer level's;
//   0 for level 0.
// - With freeze_fins, one more level after the coarsest: the coarsest mesh with the
//   stages of every component below the root dropped (the fins stay at rest on the
//   body, which still swims: the paper's deformations insignificant for the task,
//   skipped). Its geometric_error is the coarsest level's plus frozen_fin_error.
//
// Cost: O(triangles log triangles) per level and the distances' grid queries, once
// per species; no device work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "finflex/export.hpp"
#include "finflex/model.hpp"

namespace finflex {

constexpr std::size_t kMaxDetailLevels = 8;

struct LevelOptions {
  // Levels of the mesh, the full mesh included: 1..kMaxDetailLevels.
  std::size_t levels = 4;
  // Each level's target triangle count as a fraction of the finer level's: (0, 1).
  double triangle_ratio = 0.25;
  // One more level, the coarsest mesh with its fins frozen (the contract above); none
  // is added for a rig without stages below its root.
  bool freeze_fins = false;
  // Per parameter of the rig, the largest |value| its frames give it (for a swim rig
  // SwimModel::value_bounds()); empty: each parameter's limit. The frozen level's
  // error follows from these.
  std::vector<double> value_bounds;
  // Throws kInvalidArgument naming "levels", "triangle_ratio" or "value_bounds[i]" and
  // the value (a bound must be finite and >= 0).
  void validate() const;
};

struct DetailLevel {
  RiggedMesh model;              // the level's mesh and rig (vertices: a prefix of level 0's)
  std::size_t vertex_count = 0;  // model.vertex_count()
  std::size_t triangle_count = 0;
  double geometric_error = 0.0;  // mesh units; 0 for level 0
  bool fins_frozen = false;      // the freeze_fins level: only the root's stages
};

// How far, in mesh units, dropping the stages below the root of `model`'s rig can move
// a vertex, every parameter within `value_bounds` (one per parameter; empty: their
// limits): per vertex, the displacement each dropped stage gives its rest position at
// the bound's either sign (the largest, for a turn that grows with |value|: the bend,
// the hinge, a spine's table all at the bound), carried through the stages above it
// at most doubled by each (their stretch across the spine, 1 - z k, stays within (0, 2)
// while |z k| < 1: the swim driver's fold limit). The largest over the vertices; 0
// without such stages. kInvalidArgument "value_bounds" for a count other than the
// rig's parameters.
FINFLEX_API double frozen_fin_error(const RiggedMesh& model,
                                    const std::vector<double>& value_bounds = {});

class FINFLEX_API DetailLevels {
 public:
  DetailLevels(std::vector<DetailLevel> levels, std::vector<std::uint32_t> full_vertex_of);

  std::size_t size() const { return levels_.size(); }
  const DetailLevel& level(std::size_t k) const;  // kInvalidArgument "level" out of range
  const std::vector<DetailLevel>& levels() const { return levels_; }
  // The input mesh's vertex of each level-0 vertex.
  const std::vector<std::uint32_t>& full_vertex_of() const { return full_vertex_of_; }

 private:
  std::vector<DetailLevel> levels_;
  std::vector<std::uint32_t> full_vertex_of_;
};

// The levels of `full` (see the contract above). Errors: options.validate()'s,
// frozen_fin_error's; and
// kInvalidArgument naming "levels" when a level cannot be made coarser than the one
// before (the simplifier keeps more than 3/4 of its triangles: a mesh too small, or
// all border), e.g. "levels: level 2 keeps 380 of 412 triangles (target 103)".
FINFLEX_API DetailLevels make_detail_levels(const RiggedMesh& full, const LevelOptions& options);

}  // namespace finflex

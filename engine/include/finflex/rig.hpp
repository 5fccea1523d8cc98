// The paper's hierarchy (METHOD.md section 2): a fish is a tree of components (body,
// caudal fin, pectoral fins, ...), each a disjoint vertex subset of its parent with its
// own local frame and its own chain of deformers. A vertex goes through its own
// component's chain first, then its parent's, up to the root's (bottom-up); each
// stage works in its frame (METHOD.md section 3) and outputs feed the next stage.
//
// Two levels: RigSpec is what a rig file says (parse_rig_json); Rig is that spec
// resolved against one mesh (resolve_rig): vertex sets, frames in mesh coordinates,
// stages with parameter indices, all validated.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/bend.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

// ---------------------------------------------------------------- the rig file ---

// A frame as a rig file writes it. The root's frame is in mesh coordinates; a child's
// in its parent's local frame (so it follows the parent, and is in the parent's
// normalised lengths).
struct FrameSpec {
  enum class Mode { kAuto, kIdentity, kExplicit };
  Mode mode = Mode::kAuto;
  glm::dvec3 origin{0.0};
  glm::dvec3 x{1.0, 0.0, 0.0};   // spine direction; need not be unit
  glm::dvec3 y{0.0, 1.0, 0.0};   // made orthogonal to x; z = x cross y
  std::optional<double> length;  // s_x; omitted: the extent of the component along x
};

// Which vertices of the parent a component takes. Boxes and half-spaces are in the
// parent's local frame.
struct SelectorSpec {
  enum class Kind { kAll, kIndices, kGroup, kBox, kHalfSpace };
  Kind kind = Kind::kAll;
  std::vector<std::uint32_t> indices;  // kIndices: vertex indices of the mesh
  std::string group;                   // kGroup: a FaceGroup name (vertices of its triangles)
  glm::dvec3 box_min{0.0}, box_max{0.0};
  glm::dvec3 point{0.0}, normal{0.0};  // kHalfSpace: dot(p - point, normal) > 0
};

enum class DeformerKind {
  kBend,   // the paper's fish bend (METHOD.md section 5), `mode` paper or exact; param m
  kHinge,  // fold about the local y axis by an angle (radians) for x > 0; param angle
};

struct StageSpec {
  DeformerKind deformer = DeformerKind::kBend;
  BendMode mode = BendMode::kExact;  // kBend only
  double width = 0.0;                // kHinge only: the fold is spread over x in [0, width]
  std::string param;                 // the per-instance parameter this stage reads
};

struct ComponentSpec {
  std::string name;
  std::string parent;  // empty: the root
  SelectorSpec select;
  std::optional<FrameSpec> frame;  // children only; omitted: auto
  std::vector<StageSpec> chain;    // applied in order
};

struct RigSpec {
  FrameSpec frame;  // the root's frame, in mesh coordinates
  std::vector<ComponentSpec> components;
};

// Parses a rig file (JSON, schema in docs/rigs.md). Errors: kFormat for malformed
// JSON, kInvalidArgument naming the component and field ("components[2] 'tail'.chain[0].deformer")
// for missing, unknown or mistyped entries. No mesh is needed: vertex-level checks
// are resolve_rig's.
RigSpec parse_rig_json(const std::string& text);
RigSpec load_rig_file(const std::string& path);  // kIo when unreadable, then as above

// ------------------------------------------------------- resolved against a mesh ---

struct RigStage {
  DeformerKind deformer = DeformerKind::kBend;
  BendMode mode = BendMode::kExact;
  double width = 0.0;     // hinge width, in the stage frame's normalised lengths
  std::size_t param = 0;  // index into Rig::params
  BodyFrame frame;        // in mesh coordinates
  double x_max = 0.0;     // largest |x| of the rest vertices this stage moves (its
                          // component and descendants), in its frame: bend range (13)
};

struct RigComponent {
  std::string name;
  int parent = -1;                      // index into Rig::components; -1 for the root
  std::vector<std::uint32_t> vertices;  // its own vertices (not its descendants'), ascending
  BodyFrame frame;                      // in mesh coordinates
  std::vector<RigStage> chain;
};

struct Rig {
  // Depth-first order: a parent comes before its children, and a component's
  // subtree is contiguous (components[i .. subtree_end[i]) ).
  std::vector<RigComponent> components;
  std::vector<std::size_t> subtree_end;
  std::vector<std::string> params;  // parameter names, in order of first use

  // Index of a parameter by name; throws kInvalidArgument naming it when unknown.
  std::size_t param_index(const std::string& name) const;
  // The stages a vertex of component c goes through, bottom-up: c's chain, then its
  // parent's, ... then the root's. Pairs of (component index, stage index).
  std::vector<std::pair<std::size_t, std::size_t>> path(std::size_t component) const;
  // Depth of component c (the root is 0).
  std::size_t depth(std::size_t component) const;
};

// Resolves `spec` against `mesh`: selects each component's vertices from its parent's,
// finds or places its frame, and validates everything. Errors are kInvalidArgument
// with the field "components[i] 'name'.<field>" and a message naming the problem:
// no root or several roots, a root that does not select "all", an unknown parent,
// a cycle, a child that takes a vertex outside its parent, two siblings taking the
// same vertex, an empty selection, an unknown group, an index out of range, a
// degenerate frame (zero or parallel x/y, length <= 0), a hinge width < 0.
Rig resolve_rig(const RigSpec& spec, const Mesh& mesh);

// A rig with one component, "body", selecting all vertices with `frame`, and one bend
// stage of `mode` reading the parameter "m": the plain `finflex deform --m`.
Rig single_bend_rig(const Mesh& mesh, const BodyFrame& frame, BendMode mode);

}  // namespace finflex

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
//  kExplicit: x is normalised, y made orthogonal to x (Gram-Schmidt) and normalised,
//    z = x cross y; length given, or the extent (max - min along x) of the component's
//    vertices, its descendants' included. A child's origin, x, y and length are
//    converted with the parent's frame (point_to_mesh, vector_to_mesh, length times
//    the parent's length).
//  kIdentity: root: BodyFrame::identity() (the mesh is already in its body frame);
//    child: the parent's frame itself (the identity in the parent's local frame).
//  kAuto: root: find_body_frame(mesh) on the whole mesh. Child (S: its vertices,
//    descendants' included):
//    - origin, the attachment: the centroid of the vertices of S that share a triangle
//      with a vertex outside S (its seam with the rest of the mesh); if there are none
//      (a separate piece, e.g. a fin mesh of its own), the vertex of S closest to the
//      parent frame's origin;
//    - x: from the origin towards the centroid of S (an error if they coincide);
//    - y: the parent's axis_y made orthogonal to x; if less than 0.1 of it is left (x
//      within ~5.7 degrees of it), the parent's axis_z made orthogonal to x instead;
//    - length: the extent of S along x (max - min).
//    It moves with the mesh: rotating and translating the mesh and the root's frame
//    rotates and translates every child frame the same way.
struct FrameSpec {
  enum class Mode { kAuto, kIdentity, kExplicit };
  Mode mode = Mode::kAuto;
  glm::dvec3 origin{0.0};
  glm::dvec3 x{1.0, 0.0, 0.0};   // spine direction; need not be unit
  glm::dvec3 y{0.0, 1.0, 0.0};   // made orthogonal to x; z = x cross y
  std::optional<double> length;  // s_x; omitted: the extent of the component along x
};

// Which vertices of the parent a component takes (from all of the parent's vertices,
// its other children's included). Boxes (inclusive) and half-spaces are tested in the
// parent's local frame; indices and groups must lie inside the parent. The root takes
// kAll.
struct SelectorSpec {
  enum class Kind { kAll, kIndices, kGroup, kBox, kHalfSpace };
  Kind kind = Kind::kAll;
  std::vector<std::uint32_t> indices;  // kIndices: vertex indices of the mesh
  std::string group;                   // kGroup: a FaceGroup name (vertices of its triangles,
                                       // over all of the mesh's groups of that name)
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
  std::optional<FrameSpec> frame;  // children only (the root's: RigSpec::frame); omitted: auto
  std::vector<StageSpec> chain;    // applied in order; may be empty
};

struct RigSpec {
  FrameSpec frame;  // the root's frame, in mesh coordinates
  std::vector<ComponentSpec> components;
};

// Parses a rig file (JSON):
//   {"frame": <frame>,                      optional, default {"mode": "auto"}
//    "components": [
//      {"name": "body", "select": "all",
//       "chain": [{"deformer": "bend", "mode": "exact", "param": "body_m"}]},
//      {"name": "tail", "parent": "body", "select": <selector>, "frame": <frame>,
//       "chain": [{"deformer": "hinge", "width": 0.05, "param": "tail_angle"}]}]}
//   <frame>:    {"mode": "auto"} | {"mode": "identity"} |
//               {["mode": "explicit",] "origin": [x, y, z], "x": [..], "y": [..]
//                [, "length": s > 0]}
//   <selector>: "all" | {"indices": [i, ...]} | {"group": "name"} |
//               {"box": {"min": [..], "max": [..]}} |
//               {"half_space": {"point": [..], "normal": [..]}}
//   stages:     "bend" with "mode" "paper" | "exact" (default exact); "hinge" with
//               "width" >= 0 (default 0); "param" (a non-empty name) is required.
// "name", "select" and "chain" are required ("chain" may be []); "parent" is omitted
// on the root only; "frame" is not allowed on the root. Every key must be known and
// appear once per object: a typo is an error, never ignored.
// Errors: kFormat (field "rig") for malformed JSON, with the parser's line and
// column; kInvalidArgument naming the place, e.g. "components[1] 'tail'.select.box.min"
// ("components[1].name" before the name is known; "frame.x" at the top level), the
// value found and what was expected, for a missing, unknown, duplicated or mistyped
// key, an unknown deformer, mode or selector, a length <= 0, a width < 0, a box with
// max < min, a frame on the root. No mesh is needed: names, parents, vertices and
// frame geometry (zero or parallel axes) are resolve_rig's to check.
RigSpec parse_rig_json(const std::string& text);
// Reads and parses a rig file: kIo (field "path") when it cannot be read, then as
// parse_rig_json, with the path in front of the message.
RigSpec load_rig_file(const std::string& path);

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

  // Index of a parameter by name; throws kInvalidArgument (field: the name) when unknown.
  std::size_t param_index(const std::string& name) const;
  // The stages a vertex of component c goes through, bottom-up: c's chain, then its
  // parent's, ... then the root's. Pairs of (component index, stage index).
  // kInvalidArgument (field "component") when c is out of range; so does depth().
  std::vector<std::pair<std::size_t, std::size_t>> path(std::size_t component) const;
  // Depth of component c (the root is 0).
  std::size_t depth(std::size_t component) const;
};

// Resolves `spec` against `mesh`: selects each component's vertices from its parent's,
// finds or places its frame (FrameSpec), and validates everything. A component's own
// vertices are its selection minus its children's. Errors are kInvalidArgument with
// the field "components[i] 'name'.<field>" (i the spec index) and a message naming
// the problem and the values: no components or no root ("components"), several roots
// (".parent" of the second), an empty or repeated name (".name"), an unknown parent,
// a cycle (".parent" of the loop's first component, the loop in the message), a root
// that does not select "all" or has a frame, a child that takes a vertex outside its
// parent, two siblings taking the same vertex (".select" of the later one, naming
// both), an empty selection, an unknown group (listing the mesh's groups), an index
// out of range, a zero normal, a degenerate frame (".frame.x", ".frame.y",
// ".frame.length": zero or parallel x/y, length <= 0 or no extent; the root's frame
// as "frame.x" etc. with the root named in the message; an automatic child frame
// whose attachment and centroid coincide: ".frame"), an empty param or a hinge width
// < 0 (".chain[k].param" / ".width"). Also: the mesh fails validate_mesh()
// (kInvalidMesh); a group beyond the triangles (kInvalidMesh, "groups[g]"); the
// automatic root frame fails (find_body_frame's code and field, "frame" in the
// message).
Rig resolve_rig(const RigSpec& spec, const Mesh& mesh);

// A rig with one component, "body", selecting all vertices with `frame`, and one bend
// stage of `mode` reading the parameter "m": the plain `finflex deform --m`.
// Errors: validate_mesh's; BodyFrame::validate's with "frame." in front of the field.
Rig single_bend_rig(const Mesh& mesh, const BodyFrame& frame, BendMode mode);

}  // namespace finflex

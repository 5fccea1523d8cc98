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

#include "finflex/body_frame.hpp"
#include "finflex/deformer_type.hpp"
#include "finflex/export.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

// Limits, so that the work and memory a rig takes follow its size (nothing in rig
// parsing or resolution recurses): beyond them parse_rig_json, resolve_rig and
// RiggedMesh refuse the rig with kInvalidArgument naming the limit.
// Deepest nesting of a component below the root (the root's depth is 0).
constexpr std::size_t kMaxRigDepth = 64;
// Most stages on one vertex's path (its component's chain, then its ancestors').
constexpr std::size_t kMaxRigPathStages = 256;
// Deepest nesting of arrays and objects in a rig file (the schema needs 6).
constexpr std::size_t kMaxRigJsonDepth = 64;

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

// One stage of a chain: a registered deformer (finflex/deformer_type.hpp) with its
// options, reading the per-instance parameter `param`.
struct StageSpec {
  const DeformerType* deformer = nullptr;
  StageOptions options{};  // in the order of deformer->options
  std::string param;       // the per-instance parameter this stage reads
};

// A stage of the registered deformer `deformer` reading `param`, its options at their
// defaults. kInvalidArgument (field "deformer") naming the registered ones when unknown.
FINFLEX_API StageSpec make_stage(const std::string& deformer, const std::string& param);
// Sets an option of the stage's deformer by key: a number (checked against the
// option's range), or one of a choice's names. kInvalidArgument naming the key.
FINFLEX_API void set_option(StageSpec& stage, const std::string& key, double value);
FINFLEX_API void set_option(StageSpec& stage, const std::string& key, const std::string& choice);

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
//   stages:     {"deformer": <a registered name>, "param": <a non-empty name>,
//                <the deformer's options>}: "bend" with "mode" "paper" | "exact"
//               (default exact); "hinge" with "width" >= 0 (default 0); every
//               deformer's options are in the registry (finflex/deformer_type.hpp).
// "name", "select" and "chain" are required ("chain" may be []); "parent" is omitted
// on the root only; "frame" is not allowed on the root. Every key must be known and
// appear once per object: a typo is an error, never ignored.
// Errors: kFormat (field "rig") for malformed JSON, with the parser's line and
// column; kInvalidArgument (field: the place) for arrays and objects nested deeper
// than kMaxRigJsonDepth; kInvalidArgument naming the place, e.g.
// "components[1] 'tail'.select.box.min" ("components[1].name" before the name is
// known; "frame.x" at the top level), the
// value found and what was expected, for a missing, unknown, duplicated or mistyped
// key, an unknown deformer or selector, an option of another deformer, an option
// value outside its range or choices, a length <= 0, a box with max < min, a frame
// on the root. No mesh is needed: names, parents, vertices and
// frame geometry (zero or parallel axes) are resolve_rig's to check.
FINFLEX_API RigSpec parse_rig_json(const std::string& text);
// Reads and parses a rig file: kIo (field "path") when it cannot be read or is not a
// regular file (a directory, a FIFO, a device: refused without reading or blocking),
// then as parse_rig_json, with the path in front of the message.
FINFLEX_API RigSpec load_rig_file(const std::string& path);

// ------------------------------------------------------- resolved against a mesh ---

struct RigStage {
  const DeformerType* deformer = nullptr;
  StageOptions options{};
  std::size_t param = 0;  // index into Rig::parameters
  BodyFrame frame;        // in mesh coordinates
  // The rest vertices this stage moves (its component's and its descendants') in its
  // frame: their extent along x, and the deformer's measurements.
  StageGeometry geometry;
};

struct RigComponent {
  std::string name;
  int parent = -1;                      // index into Rig::components; -1 for the root
  std::vector<std::uint32_t> vertices;  // its own vertices (not its descendants'), ascending
  BodyFrame frame;                      // in mesh coordinates
  std::vector<RigStage> chain;
};

// A per-instance parameter: `count` consecutive values of each instance's row, from
// `offset` on (one for a bend's m or a hinge's angle).
struct RigParameter {
  std::string name;
  std::size_t offset = 0;
  std::size_t count = 1;
  // The largest |value| accepted: the tightest of the stages that read it
  // (DeformerType::value_limit for their geometry), and which stage sets it, for messages
  // ("set by the bend of 'body': |m| <= 0.5 / x_max (13), x_max = 0.489").
  double limit = 0.0;
  std::string limit_source;
};

// A stage by its place in the rig: component index and position in its chain.
struct StageRef {
  std::size_t component = 0;
  std::size_t stage = 0;

  bool operator==(const StageRef& other) const {
    return component == other.component && stage == other.stage;
  }
};

struct FINFLEX_API Rig {
  // Depth-first order: a parent comes before its children, and a component's
  // subtree is contiguous (components[i .. subtree_end[i]) ).
  std::vector<RigComponent> components;
  std::vector<std::size_t> subtree_end;
  std::vector<RigParameter> parameters;  // in order of first use

  // Values per instance: the sum of the parameters' counts.
  std::size_t values_per_instance() const;
  // Index of a parameter by name; throws kInvalidArgument (field: the name) when unknown.
  std::size_t param_index(const std::string& name) const;
  const RigStage& stage(StageRef ref) const { return components[ref.component].chain[ref.stage]; }
  // The stages a vertex of component c goes through, bottom-up: c's chain, then its
  // parent's, ... then the root's.
  // kInvalidArgument (field "component") when c is out of range; so does depth(); and
  // (field "components[k].parent") when a parent on the way does not come before its
  // child (depth-first order), so a hand-made rig with a cycle cannot loop.
  std::vector<StageRef> path(std::size_t component) const;
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
// whose attachment and centroid coincide: ".frame"), an empty param, a stage without a
// deformer or with an option outside its range (".chain[k].param", ".deformer",
// ".<option>"), a parameter read by stages that take different numbers of values
// (".chain[k].param"), a component nested deeper than kMaxRigDepth (".parent"), a
// path of more than kMaxRigPathStages stages (".chain"). Also: the mesh fails
// validate_mesh() (kInvalidMesh); a group beyond the triangles (kInvalidMesh,
// "groups[g]"); the automatic root frame fails (find_body_frame's code and field,
// "frame" in the message). Work is O(components + stages + the vertices each
// component selects + the triangles around automatic child frames), without
// recursion; messages list at most 20 names.
FINFLEX_API Rig resolve_rig(const RigSpec& spec, const Mesh& mesh);

// The two forms of the paper's bend (METHOD.md section 5), the bend's "mode" option.
enum class BendMode {
  kPaper,  // the paper's 4th-order Maclaurin series (15)-(17): no arcsin
  kExact,  // the closed-form integral of (13): x' = x sqrt(1 - 4m^2x^2)/2 + asin(2mx)/(4m)
};
FINFLEX_API const char* to_string(BendMode mode);
// Parses "paper" / "exact"; errors name `field` and the value.
FINFLEX_API BendMode parse_bend_mode(const std::string& text, const std::string& field = "mode");
// The largest valid |m| of a bend whose vertices reach |x| <= x_max (13): 0.5 / x_max.
FINFLEX_API double max_abs_m(double x_max);

// A rig with one component, "body", selecting all vertices with `frame`, and one bend
// stage of `mode` reading the parameter "m": the paper's whole-body bend
// (`finflex deform --m`). The OpenCL backend runs it with its single-bend kernel.
// Errors: validate_mesh's; BodyFrame::validate's with "frame." in front of the field.
FINFLEX_API Rig single_bend_rig(const Mesh& mesh, const BodyFrame& frame, BendMode mode);

}  // namespace finflex

// RigSpec + Mesh -> Rig: the component tree, each component's vertices and frame, the
// stages with their parameter indices and bend ranges (contracts in finflex/rig.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/body_frame.hpp"
#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "finflex/rig.hpp"
#include "rig/tree.hpp"

namespace finflex {
namespace {

using detail::component_field;
using detail::kNoComponent;
using detail::RigTree;
constexpr auto fail = detail::fail_rig;
// |sin| of the angle between a frame's y and x below which y is taken as parallel.
constexpr double kParallelTolerance = 1e-6;
// Automatic child frames: when the parent's axis_y has less than this much left
// across the child's x (x within ~5.7 degrees of it), the parent's axis_z gives y.
constexpr double kAutoYTolerance = 0.1;
// Automatic child frames: the attachment and the centroid coincide when closer than
// this fraction of the component's bounding-box diagonal.
constexpr double kCoincideTolerance = 1e-9;

// ---------------------------------------------------------------------------------
// Formatting and errors

std::string format_double(double value) {
  std::ostringstream out;
  out.precision(9);
  out << value;
  return out.str();
}

std::string format_vec(const glm::dvec3& v) {
  return "(" + format_double(v.x) + ", " + format_double(v.y) + ", " + format_double(v.z) + ")";
}

bool is_finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 position(const Mesh& mesh, std::uint32_t v) { return glm::dvec3(mesh.positions[v]); }

// ---------------------------------------------------------------------------------
// Vertex selection. A set is a sorted vector of vertex indices.

using VertexSet = std::vector<std::uint32_t>;

// Flags over all vertices, allocated once per resolve_rig and set and cleared for one
// vertex set at a time: O(set size) per use, not O(vertex count).
class VertexFlags {
 public:
  explicit VertexFlags(std::size_t vertex_count) : flags_(vertex_count, 0) {}
  void set(const VertexSet& set) {
    for (const std::uint32_t v : set) flags_[v] = 1;
  }
  void clear(const VertexSet& set) {
    for (const std::uint32_t v : set) flags_[v] = 0;
  }
  bool operator[](std::uint32_t v) const { return flags_[v] != 0; }

 private:
  std::vector<char> flags_;
};

// The triangles around each vertex (compressed rows): triangles_of(v).
class VertexTriangles {
 public:
  explicit VertexTriangles(const Mesh& mesh) : first_(mesh.vertex_count() + 1, 0) {
    for (const std::uint32_t v : mesh.indices) ++first_[v + 1];
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) first_[v + 1] += first_[v];
    triangles_.resize(mesh.indices.size());
    std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
    for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
      triangles_[next[mesh.indices[k]]++] = static_cast<std::uint32_t>(k / 3);
    }
  }
  template <typename Visit>
  void for_each(std::uint32_t v, Visit visit) const {
    for (std::size_t k = first_[v]; k < first_[v + 1]; ++k) visit(triangles_[k]);
  }

 private:
  std::vector<std::size_t> first_;
  std::vector<std::uint32_t> triangles_;
};

// What a child selects from its parent: the parent's subtree vertices, their flags,
// its mesh-space frame and its name (for messages).
struct ParentView {
  const VertexSet* vertices;
  const VertexFlags* in;
  const BodyFrame* frame;
  std::string name;
};

VertexSet sorted_unique(VertexSet set) {
  std::sort(set.begin(), set.end());
  set.erase(std::unique(set.begin(), set.end()), set.end());
  return set;
}

VertexSet select_indices(const Mesh& mesh, const SelectorSpec& select, const ParentView& parent,
                         const std::string& field) {
  const std::string indices_field = field + ".indices";
  for (std::size_t k = 0; k < select.indices.size(); ++k) {
    const std::uint32_t v = select.indices[k];
    const std::string at = indices_field + "[" + std::to_string(k) + "]";
    if (v >= mesh.vertex_count()) {
      fail(at, "vertex " + std::to_string(v) + " is out of range (the mesh has " +
                   std::to_string(mesh.vertex_count()) + " vertices)");
    }
    if (!(*parent.in)[v]) {
      fail(at, "vertex " + std::to_string(v) + " is outside the parent '" + parent.name +
                   "' (a child selects from its parent's vertices)");
    }
  }
  return sorted_unique(select.indices);
}

VertexSet select_group(const Mesh& mesh, const SelectorSpec& select, const ParentView& parent,
                       const std::string& field) {
  const std::string group_field = field + ".group";
  VertexSet set;
  bool found = false;
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    const FaceGroup& group = mesh.groups[g];
    if (group.name != select.group) continue;
    found = true;
    if (group.first_triangle > mesh.triangle_count() ||
        group.triangle_count > mesh.triangle_count() - group.first_triangle) {
      const std::string at = "groups[" + std::to_string(g) + "]";
      throw Error(ErrorCode::kInvalidMesh, at,
                  at + ": group '" + group.name + "' (triangles " +
                      std::to_string(group.first_triangle) + " + " +
                      std::to_string(group.triangle_count) + ") exceeds the mesh's " +
                      std::to_string(mesh.triangle_count()) + " triangles");
    }
    const std::size_t begin = 3 * group.first_triangle;
    const std::size_t end = begin + 3 * group.triangle_count;
    set.insert(set.end(), mesh.indices.begin() + static_cast<std::ptrdiff_t>(begin),
               mesh.indices.begin() + static_cast<std::ptrdiff_t>(end));
  }
  if (!found) {
    std::vector<std::string> names;
    std::set<std::string> seen;
    for (const FaceGroup& group : mesh.groups) {
      if (seen.insert(group.name).second) names.push_back(group.name);
    }
    fail(group_field, "'" + select.group + "' is not a face group of the mesh (" +
                          (names.empty() ? std::string("the mesh has no groups: OBJ g/o lines "
                                                       "or glTF primitives name them")
                                         : "its groups: " + detail::short_list(names, "'")) +
                          ")");
  }
  set = sorted_unique(std::move(set));
  for (const std::uint32_t v : set) {
    if (!(*parent.in)[v]) {
      fail(group_field, "group '" + select.group + "' takes vertex " + std::to_string(v) +
                            ", which is outside the parent '" + parent.name +
                            "' (a child selects from its parent's vertices)");
    }
  }
  return set;
}

// Box and half-space: tested on the parent's vertices in the parent's local frame.
VertexSet select_region(const Mesh& mesh, const SelectorSpec& select, const ParentView& parent,
                        const std::string& field) {
  const bool box = select.kind == SelectorSpec::Kind::kBox;
  if (box) {
    if (!is_finite(select.box_min)) {
      fail(field + ".box.min", "= " + format_vec(select.box_min) + " is not finite");
    }
    if (!is_finite(select.box_max)) {
      fail(field + ".box.max", "= " + format_vec(select.box_max) + " is not finite");
    }
  } else {
    if (!is_finite(select.point)) {
      fail(field + ".half_space.point", "= " + format_vec(select.point) + " is not finite");
    }
    if (!is_finite(select.normal) || !(glm::length(select.normal) > 0.0)) {
      fail(field + ".half_space.normal",
           "= " + format_vec(select.normal) + " must be a finite, non-zero direction");
    }
  }
  VertexSet set;
  for (const std::uint32_t v : *parent.vertices) {
    const glm::dvec3 p = parent.frame->point_to_local(position(mesh, v));
    const bool inside = box ? glm::all(glm::greaterThanEqual(p, select.box_min)) &&
                                  glm::all(glm::lessThanEqual(p, select.box_max))
                            : glm::dot(p - select.point, select.normal) > 0.0;
    if (inside) set.push_back(v);
  }
  return set;
}

std::string describe(const SelectorSpec& select) {
  switch (select.kind) {
    case SelectorSpec::Kind::kAll:
      return "\"all\"";
    case SelectorSpec::Kind::kIndices:
      return std::to_string(select.indices.size()) + " indices";
    case SelectorSpec::Kind::kGroup:
      return "group '" + select.group + "'";
    case SelectorSpec::Kind::kBox:
      return "box min " + format_vec(select.box_min) + " max " + format_vec(select.box_max);
    case SelectorSpec::Kind::kHalfSpace:
      return "half-space point " + format_vec(select.point) + " normal " +
             format_vec(select.normal);
  }
  return "?";
}

// A child's subtree vertices, from its parent's (field: the component's).
VertexSet select_vertices(const Mesh& mesh, const ComponentSpec& component,
                          const ParentView& parent, const std::string& field) {
  const std::string select_field = field + ".select";
  VertexSet set;
  switch (component.select.kind) {
    case SelectorSpec::Kind::kAll:
      set = *parent.vertices;
      break;
    case SelectorSpec::Kind::kIndices:
      set = select_indices(mesh, component.select, parent, select_field);
      break;
    case SelectorSpec::Kind::kGroup:
      set = select_group(mesh, component.select, parent, select_field);
      break;
    case SelectorSpec::Kind::kBox:
    case SelectorSpec::Kind::kHalfSpace:
      set = select_region(mesh, component.select, parent, select_field);
      break;
  }
  if (set.empty()) {
    fail(select_field, describe(component.select) + " selects no vertex of the parent '" +
                           parent.name + "' (" + std::to_string(parent.vertices->size()) +
                           " vertices; boxes and half-spaces are in the parent's local frame)");
  }
  return set;
}

// ---------------------------------------------------------------------------------
// Frames

// [min, max] of (p - origin) . axis over `vertices`.
std::pair<double, double> extent(const Mesh& mesh, const VertexSet& vertices,
                                 const glm::dvec3& origin, const glm::dvec3& axis) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const std::uint32_t v : vertices) {
    const double x = glm::dot(position(mesh, v) - origin, axis);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

glm::dvec3 centroid(const Mesh& mesh, const VertexSet& vertices) {
  glm::dvec3 sum{0.0};
  for (const std::uint32_t v : vertices) sum += position(mesh, v);
  return sum / static_cast<double>(vertices.size());
}

// Unit x and y (y made orthogonal to x) of an explicit frame as written; `field` is
// the frame's ("frame", "components[1] 'tail'.frame"), `note` ends the messages.
std::pair<glm::dvec3, glm::dvec3> explicit_axes(const FrameSpec& spec, const std::string& field,
                                                const std::string& note) {
  if (!is_finite(spec.origin)) {
    fail(field + ".origin", "= " + format_vec(spec.origin) + " is not finite" + note);
  }
  const double x_norm = glm::length(spec.x);
  if (!is_finite(spec.x) || !(x_norm > 0.0)) {
    fail(field + ".x", "= " + format_vec(spec.x) + " must be a finite, non-zero direction" + note);
  }
  const glm::dvec3 x = spec.x / x_norm;
  if (!is_finite(spec.y)) fail(field + ".y", "= " + format_vec(spec.y) + " is not finite" + note);
  const glm::dvec3 across = spec.y - glm::dot(spec.y, x) * x;
  const double across_norm = glm::length(across);
  if (!(across_norm > kParallelTolerance * glm::length(spec.y))) {
    fail(field + ".y", "= " + format_vec(spec.y) + " is zero or parallel to x = " +
                           format_vec(spec.x) + ": it cannot fix the dorsal direction" + note);
  }
  return {x, across / across_norm};
}

double checked_length(double length, const std::string& field, const std::string& note) {
  if (!std::isfinite(length) || !(length > 0.0)) {
    fail(field + ".length", "= " + format_double(length) + " must be finite and > 0" + note);
  }
  return length;
}

// A frame from mesh-space origin and unit, orthogonal x and y; length given or the
// extent of `subtree` along x.
BodyFrame assemble(const Mesh& mesh, const VertexSet& subtree, const glm::dvec3& origin,
                   const glm::dvec3& x, const glm::dvec3& y, std::optional<double> length,
                   const std::string& field, const std::string& note) {
  BodyFrame frame;
  frame.origin = origin;
  frame.axis_x = x;
  frame.axis_y = y;
  frame.axis_z = glm::cross(x, y);
  if (length) {
    frame.length = *length;
  } else {
    const auto [lo, hi] = extent(mesh, subtree, origin, x);
    frame.length = hi - lo;
    if (!(frame.length > 0.0)) {
      fail(field + ".length", "omitted, and the component's vertices have no extent along x = " +
                                  format_vec(x) + ": give the length" + note);
    }
  }
  try {
    frame.validate();
  } catch (const Error& e) {  // cannot happen after the checks above; never let it pass
    fail(field + "." + e.field(), e.what() + note);
  }
  return frame;
}

// The root's frame (in mesh coordinates); the root owns every vertex.
BodyFrame root_frame(const Mesh& mesh, const RigSpec& spec, const RigTree& tree,
                     const VertexSet& all) {
  const std::string note =
      " (frame of the root component '" + spec.components[tree.root].name + "')";
  switch (spec.frame.mode) {
    case FrameSpec::Mode::kAuto:
      try {
        return find_body_frame(mesh);
      } catch (const Error& e) {
        throw Error(e.code(), e.field(),
                    std::string("frame: the automatic body frame") + note + " failed: " + e.what() +
                        " (give the frame explicitly)");
      }
    case FrameSpec::Mode::kIdentity:
      return BodyFrame::identity();
    case FrameSpec::Mode::kExplicit:
      break;
  }
  const auto [x, y] = explicit_axes(spec.frame, "frame", note);
  std::optional<double> length;
  if (spec.frame.length) length = checked_length(*spec.frame.length, "frame", note);
  return assemble(mesh, all, spec.frame.origin, x, y, length, "frame", note);
}

// What resolving reuses from one component to the next, allocated once: vertex flags,
// the owner of each vertex among a parent's children, and (built for the first
// automatic child frame) the triangles around each vertex.
struct Scratch {
  explicit Scratch(const Mesh& mesh)
      : in_parent(mesh.vertex_count()),
        in_child(mesh.vertex_count()),
        taken_by(mesh.vertex_count(), kNoComponent) {}
  VertexFlags in_parent, in_child;
  std::vector<std::size_t> taken_by;
  std::optional<VertexTriangles> around;
};

// The vertices of `subtree` (flagged in `in`) on its boundary with the rest of the
// mesh: those sharing a triangle with a vertex outside it. Ascending, like `subtree`;
// O(triangles around the subtree).
VertexSet boundary(const Mesh& mesh, const VertexSet& subtree, const VertexFlags& in,
                   const VertexTriangles& around) {
  VertexSet set;
  for (const std::uint32_t v : subtree) {
    bool on = false;
    around.for_each(v, [&](std::uint32_t t) {
      for (std::size_t k = 0; k < 3; ++k) on = on || !in[mesh.indices[3 * t + k]];
    });
    if (on) set.push_back(v);
  }
  return set;
}

// The automatic frame of a child (rule in rig.hpp).
BodyFrame auto_child_frame(const Mesh& mesh, const VertexSet& subtree, const BodyFrame& parent,
                           const std::string& field, Scratch& scratch) {
  if (!scratch.around) scratch.around.emplace(mesh);
  scratch.in_child.set(subtree);
  const VertexSet attachment = boundary(mesh, subtree, scratch.in_child, *scratch.around);
  scratch.in_child.clear(subtree);
  glm::dvec3 origin{0.0};
  if (!attachment.empty()) {
    origin = centroid(mesh, attachment);
  } else {  // a separate piece: its vertex closest to the parent's origin
    double best = std::numeric_limits<double>::infinity();
    for (const std::uint32_t v : subtree) {
      const double d = glm::length(position(mesh, v) - parent.origin);
      if (d < best) {
        best = d;
        origin = position(mesh, v);
      }
    }
  }
  const glm::dvec3 towards = centroid(mesh, subtree) - origin;
  glm::dvec3 lo(std::numeric_limits<double>::infinity());
  glm::dvec3 hi = -lo;
  for (const std::uint32_t v : subtree) {
    lo = glm::min(lo, position(mesh, v));
    hi = glm::max(hi, position(mesh, v));
  }
  const double size = glm::length(hi - lo);
  if (!(glm::length(towards) > kCoincideTolerance * size)) {
    fail(field, "automatic frame: the component's centroid coincides with its attachment " +
                    format_vec(origin) + ", so its x axis is undefined (" +
                    std::to_string(subtree.size()) + " vertices): give the frame explicitly");
  }
  const glm::dvec3 x = glm::normalize(towards);
  glm::dvec3 y = parent.axis_y - glm::dot(parent.axis_y, x) * x;
  if (glm::length(y) < kAutoYTolerance) y = parent.axis_z - glm::dot(parent.axis_z, x) * x;
  return assemble(mesh, subtree, origin, x, glm::normalize(y), std::nullopt, field, "");
}

// A child's frame in mesh coordinates, from its spec (in the parent's local frame).
BodyFrame child_frame(const Mesh& mesh, const ComponentSpec& component, const VertexSet& subtree,
                      const BodyFrame& parent, const std::string& component_field_name,
                      Scratch& scratch) {
  const std::string field = component_field_name + ".frame";
  if (!component.frame || component.frame->mode == FrameSpec::Mode::kAuto) {
    return auto_child_frame(mesh, subtree, parent, field, scratch);
  }
  if (component.frame->mode == FrameSpec::Mode::kIdentity) return parent;
  const FrameSpec& spec = *component.frame;
  const auto [x, y] = explicit_axes(spec, field, " (in the parent's local frame)");
  std::optional<double> length;
  if (spec.length) {
    length = checked_length(*spec.length, field, " (in the parent's local frame)") * parent.length;
  }
  const glm::dvec3 mesh_x = glm::normalize(parent.vector_to_mesh(x));
  glm::dvec3 mesh_y = parent.vector_to_mesh(y);
  mesh_y = glm::normalize(mesh_y - glm::dot(mesh_y, mesh_x) * mesh_x);
  return assemble(mesh, subtree, parent.point_to_mesh(spec.origin), mesh_x, mesh_y, length, field,
                  "");
}

// ---------------------------------------------------------------------------------
// Walking the tree

// The rest vertices in `frame`.
std::vector<glm::dvec3> local_positions(const Mesh& mesh, const VertexSet& vertices,
                                        const BodyFrame& frame) {
  std::vector<glm::dvec3> local;
  local.reserve(vertices.size());
  for (const std::uint32_t v : vertices) local.push_back(frame.point_to_local(position(mesh, v)));
  return local;
}

// The extent along x of `local` (and the deformer's measurements of it).
StageGeometry measure_stage(const std::vector<glm::dvec3>& local, const StageSpec& stage) {
  StageGeometry geometry;
  if (!local.empty()) {
    geometry.x_lowest = geometry.x_highest = local.front().x;
  }
  for (const glm::dvec3& p : local) {
    geometry.x_lowest = std::min(geometry.x_lowest, p.x);
    geometry.x_highest = std::max(geometry.x_highest, p.x);
    geometry.x_max = std::max(geometry.x_max, std::abs(p.x));
  }
  if (stage.deformer->measure)
    geometry.measurements = stage.deformer->measure(stage.options, local);
  return geometry;
}

// The geometry of each stage of component c's chain (its options checked already, by
// collect_parameters), over `subtree` in `frame`.
std::vector<StageGeometry> measure_chain(const Mesh& mesh, const RigSpec& spec, std::size_t c,
                                         const VertexSet& subtree, const BodyFrame& frame) {
  const std::vector<StageSpec>& chain = spec.components[c].chain;
  const std::vector<glm::dvec3> local = local_positions(mesh, subtree, frame);
  std::vector<StageGeometry> geometry;
  geometry.reserve(chain.size());
  for (const StageSpec& stage : chain) geometry.push_back(measure_stage(local, stage));
  return geometry;
}

// Per spec component: its subtree vertices (until its children are resolved), own
// vertices, frame, and its stages' geometry over its subtree in its frame.
struct Resolved {
  std::vector<VertexSet> subtree;
  std::vector<VertexSet> own;
  std::vector<BodyFrame> frame;
  std::vector<std::vector<StageGeometry>> geometry;
};

// Selects the children of `c` (whose subtree and frame are known) and places their
// frames; fills own[c] and geometry[c], then releases subtree[c]. Called in depth-first
// order, so the subtrees held at any time are disjoint: memory stays O(vertices).
void resolve_children(const Mesh& mesh, const RigSpec& spec, const RigTree& tree, std::size_t c,
                      Scratch& scratch, Resolved& out) {
  const VertexSet& subtree = out.subtree[c];
  out.geometry[c] = measure_chain(mesh, spec, c, subtree, out.frame[c]);
  if (tree.children[c].empty()) {
    out.own[c] = std::move(out.subtree[c]);
    return;
  }
  scratch.in_parent.set(subtree);
  const ParentView parent{&subtree, &scratch.in_parent, &out.frame[c], spec.components[c].name};
  std::vector<std::size_t>& taken_by = scratch.taken_by;
  for (const std::size_t child : tree.children[c]) {
    const std::string field = component_field(spec, child);
    out.subtree[child] = select_vertices(mesh, spec.components[child], parent, field);
    for (const std::uint32_t v : out.subtree[child]) {
      if (taken_by[v] != kNoComponent) {
        fail(field + ".select", "takes vertex " + std::to_string(v) + ", which its sibling '" +
                                    spec.components[taken_by[v]].name + "' (components[" +
                                    std::to_string(taken_by[v]) +
                                    "]) also takes: siblings must be disjoint");
      }
      taken_by[v] = child;
    }
    out.frame[child] =
        child_frame(mesh, spec.components[child], out.subtree[child], out.frame[c], field, scratch);
  }
  for (const std::uint32_t v : subtree) {
    if (taken_by[v] == kNoComponent) out.own[c].push_back(v);
  }
  for (const std::size_t child : tree.children[c]) {
    for (const std::uint32_t v : out.subtree[child]) taken_by[v] = kNoComponent;
  }
  scratch.in_parent.clear(subtree);
  VertexSet().swap(out.subtree[c]);
}

// The per-instance parameters in order of first use (components and chains in spec
// order), each with the count of values its stages read; limits come later.
// `index_of` receives each parameter's index by name.
void check_options(const RigSpec& spec, std::size_t c, std::size_t k);  // below

std::vector<RigParameter> collect_parameters(const RigSpec& spec,
                                             std::map<std::string, std::size_t>& index_of) {
  std::vector<RigParameter> parameters;
  for (std::size_t i = 0; i < spec.components.size(); ++i) {
    const std::vector<StageSpec>& chain = spec.components[i].chain;
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const std::string field = component_field(spec, i) + ".chain[" + std::to_string(k) + "]";
      const StageSpec& stage = chain[k];
      if (stage.deformer == nullptr) {
        fail(field + ".deformer", "is not set (expected one of " + deformer_type_names() + ")");
      }
      if (stage.param.empty()) {
        fail(field + ".param", "is empty: every stage names the parameter it reads");
      }
      check_options(spec, i, k);  // before the deformer reads them (value_count)
      const std::size_t count = stage.deformer->value_count(stage.options);
      const auto [it, added] = index_of.emplace(stage.param, parameters.size());
      if (added) {
        RigParameter parameter;
        parameter.name = stage.param;
        parameter.count = count;
        parameters.push_back(parameter);
      } else if (const RigParameter* found = &parameters[it->second]; found->count != count) {
        fail(field + ".param", "'" + stage.param + "' is read by stages taking " +
                                   std::to_string(found->count) + " and " + std::to_string(count) +
                                   " values: a parameter has one size");
      }
    }
  }
  std::size_t offset = 0;
  for (RigParameter& parameter : parameters) {
    parameter.offset = offset;
    offset += parameter.count;
  }
  return parameters;
}

// Checks a programmatic stage's options against its deformer's (parse_rig_json
// checks those it reads).
void check_options(const RigSpec& spec, std::size_t c, std::size_t k) {
  const StageSpec& stage = spec.components[c].chain[k];
  for (std::size_t o = 0; o < stage.deformer->options.size(); ++o) {
    const DeformerOption& option = stage.deformer->options[o];
    const double value = stage.options[o];
    const bool valid =
        option.choices.empty()
            ? (std::isfinite(value) && value >= option.minimum && value <= option.maximum &&
               (!option.integer || value == std::floor(value)))
            : (value >= 0.0 && value < double(option.choices.size()) && value == std::floor(value));
    if (!valid) {
      fail(component_field(spec, c) + ".chain[" + std::to_string(k) + "]." + option.key,
           "= " + format_double(value) + " is not a valid " + stage.deformer->name + " " +
               option.key + " (" + option.meaning + ")");
    }
  }
}

std::vector<RigStage> resolve_chain(const RigSpec& spec, std::size_t c, const Resolved& resolved,
                                    const std::map<std::string, std::size_t>& param_of) {
  std::vector<RigStage> stages;
  const BodyFrame& frame = resolved.frame[c];
  const std::vector<StageSpec>& chain = spec.components[c].chain;
  for (std::size_t k = 0; k < chain.size(); ++k) {
    RigStage out;
    out.deformer = chain[k].deformer;
    out.options = chain[k].options;
    out.param = param_of.at(chain[k].param);
    out.frame = frame;
    out.geometry = resolved.geometry[c][k];
    stages.push_back(out);
  }
  return stages;
}

// Each parameter's limit: the tightest of the stages that read it.
void set_limits(Rig& rig) {
  std::vector<bool> seen(rig.parameters.size(), false);
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      const double limit = stage.deformer->value_limit(stage.options, stage.geometry);
      RigParameter& parameter = rig.parameters[stage.param];
      if (!seen[stage.param] || limit < parameter.limit) {
        parameter.limit = limit;
        parameter.limit_source = "set by the " + std::string(stage.deformer->name) + " of '" +
                                 component.name + "': " + stage.deformer->value_meaning +
                                 ", x_max = " + format_double(stage.geometry.x_max);
      }
      seen[stage.param] = true;
    }
  }
}

void check_component(const Rig& rig, std::size_t component) {
  if (component >= rig.components.size()) {
    throw Error(ErrorCode::kInvalidArgument, "component",
                "component = " + std::to_string(component) + " is out of range (the rig has " +
                    std::to_string(rig.components.size()) + " components)");
  }
}

// The parent of component c, checked to come before it (depth-first order), so that
// every walk up the tree ends at the root in at most c steps.
std::size_t parent_of(const Rig& rig, std::size_t c) {
  const int parent = rig.components[c].parent;
  if (parent >= 0 && static_cast<std::size_t>(parent) >= c) {
    const std::string field = "components[" + std::to_string(c) + "].parent";
    throw Error(ErrorCode::kInvalidArgument, field,
                field + " = " + std::to_string(parent) +
                    ": a parent comes before its children (depth-first order)");
  }
  return parent < 0 ? kNoComponent : static_cast<std::size_t>(parent);
}

}  // namespace

// ---------------------------------------------------------------------------------

std::size_t Rig::values_per_instance() const {
  return parameters.empty() ? 0 : parameters.back().offset + parameters.back().count;
}

std::size_t Rig::param_index(const std::string& name) const {
  for (std::size_t p = 0; p < parameters.size(); ++p) {
    if (parameters[p].name == name) return p;
  }
  std::vector<std::string> names;
  names.reserve(parameters.size());
  for (const RigParameter& p : parameters) names.push_back(p.name);
  throw Error(ErrorCode::kInvalidArgument, name,
              "'" + name + "' is not a parameter of the rig (its parameters: " +
                  detail::short_list(names) + ")");
}

std::vector<StageRef> Rig::path(std::size_t component) const {
  check_component(*this, component);
  std::vector<StageRef> stages;
  for (std::size_t c = component; c != kNoComponent; c = parent_of(*this, c)) {
    for (std::size_t k = 0; k < components[c].chain.size(); ++k) stages.push_back({c, k});
  }
  return stages;
}

std::size_t Rig::depth(std::size_t component) const {
  check_component(*this, component);
  std::size_t depth = 0;
  for (std::size_t c = parent_of(*this, component); c != kNoComponent; c = parent_of(*this, c)) {
    ++depth;
  }
  return depth;
}

Rig resolve_rig(const RigSpec& spec, const Mesh& mesh) {
  validate_mesh(mesh);
  const RigTree tree = detail::build_rig_tree(spec);
  Rig rig;
  std::map<std::string, std::size_t> param_of;
  rig.parameters = collect_parameters(spec, param_of);

  const std::size_t n = spec.components.size();
  Resolved resolved;
  resolved.subtree.resize(n);
  resolved.own.resize(n);
  resolved.frame.resize(n);
  resolved.geometry.resize(n);
  VertexSet& all = resolved.subtree[tree.root];
  all.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<std::uint32_t>(v);
  resolved.frame[tree.root] = root_frame(mesh, spec, tree, all);
  Scratch scratch(mesh);
  for (const std::size_t c : tree.order) resolve_children(mesh, spec, tree, c, scratch, resolved);

  std::vector<std::size_t> position_of(n, kNoComponent);
  for (std::size_t k = 0; k < n; ++k) position_of[tree.order[k]] = k;
  rig.components.resize(n);
  rig.subtree_end.assign(n, 0);
  std::vector<std::size_t> depth(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = tree.order[k];
    RigComponent& out = rig.components[k];
    out.name = spec.components[c].name;
    out.parent =
        tree.parent[c] == kNoComponent ? -1 : static_cast<int>(position_of[tree.parent[c]]);
    out.vertices = std::move(resolved.own[c]);
    out.frame = resolved.frame[c];
    out.chain = resolve_chain(spec, c, resolved, param_of);
    depth[k] = tree.depth[c];
  }
  // Subtrees are contiguous: a component's ends where the next non-descendant starts
  // (each step skips a whole child subtree: O(components) in all).
  for (std::size_t k = n; k-- > 0;) {
    std::size_t end = k + 1;
    while (end < n && depth[end] > depth[k]) end = rig.subtree_end[end];
    rig.subtree_end[k] = end;
  }
  set_limits(rig);
  return rig;
}

Rig single_bend_rig(const Mesh& mesh, const BodyFrame& frame, BendMode mode) {
  validate_mesh(mesh);
  try {
    frame.validate();
  } catch (const Error& e) {
    throw Error(e.code(), "frame." + e.field(), std::string("frame.") + e.what());
  }
  RigComponent body;
  body.name = "body";
  body.vertices.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < body.vertices.size(); ++v) {
    body.vertices[v] = static_cast<std::uint32_t>(v);
  }
  body.frame = frame;
  StageSpec spec = make_stage("bend", "m");
  set_option(spec, "mode", to_string(mode));
  RigStage stage;
  stage.deformer = spec.deformer;
  stage.options = spec.options;
  stage.param = 0;
  stage.frame = frame;
  stage.geometry = measure_stage(local_positions(mesh, body.vertices, frame), spec);
  body.chain.push_back(stage);
  Rig rig;
  rig.parameters = {RigParameter{"m", 0, 1, 0.0, ""}};
  rig.components.push_back(std::move(body));
  rig.subtree_end = {1};
  set_limits(rig);
  return rig;
}

}  // namespace finflex

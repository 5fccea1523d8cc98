// Rigs: parsing rig files (every field, every error) and resolving them against a
// mesh (tree order, vertex sets, frames, stages), on the synthetic fish, on Blub and
// on an OBJ with groups.
#include "finflex/rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "finflex/accuracy.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/model.hpp"
#include "finflex/parameters.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

using Kind = SelectorSpec::Kind;
using Mode = FrameSpec::Mode;
using VertexSet = std::vector<std::uint32_t>;

// ---------------------------------------------------------------------------------
// Helpers

std::vector<std::string> parameter_names(const Rig& rig) {
  std::vector<std::string> names;
  for (const RigParameter& parameter : rig.parameters) names.push_back(parameter.name);
  return names;
}

// Success iff `call` throws finflex::Error with `code`, exactly `field`, and a message
// that repeats the field (for "path": names the path instead) and contains
// `message_part`.
::testing::AssertionResult Fails(const std::function<void()>& call, ErrorCode code,
                                 const std::string& field, const std::string& message_part) {
  try {
    call();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (e.code() != code) {
      return ::testing::AssertionFailure() << "code " << error_code_name(e.code()) << " instead of "
                                           << error_code_name(code) << ": " << message;
    }
    if (e.field() != field) {
      return ::testing::AssertionFailure()
             << "field '" << e.field() << "' instead of '" << field << "': " << message;
    }
    if (field != "path" && message.find(field) == std::string::npos) {  // "path": the path
      return ::testing::AssertionFailure() << "message lacks the field: " << message;
    }
    if (message.find(message_part) == std::string::npos) {
      return ::testing::AssertionFailure() << "message lacks '" << message_part << "': " << message;
    }
    return ::testing::AssertionSuccess();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "not a finflex::Error: " << e.what();
  }
  return ::testing::AssertionFailure() << "nothing thrown";
}

::testing::AssertionResult Near(const glm::dvec3& actual, const glm::dvec3& expected,
                                double tolerance) {
  if (glm::length(actual - expected) <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << actual.x << ", " << actual.y << ", " << actual.z << ") vs (" << expected.x
         << ", " << expected.y << ", " << expected.z << ")";
}

// The synthetic fish: a spindle along x in [-0.5, 0.5], already in its body frame.
const Mesh& fish() {
  static const Mesh mesh = test::synthetic_fish();
  return mesh;
}

const Mesh& blub() {
  static const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  return mesh;
}

// A rig file with the given components (JSON objects, comma-separated) and top-level
// frame.
std::string rig_text(const std::string& components,
                     const std::string& frame = R"({"mode": "identity"})") {
  return R"({"frame": )" + frame + R"(, "components": [)" + components + "]}";
}

// A component object; `extra` is added verbatim (e.g. `, "frame": {...}`).
std::string component(const std::string& name, const std::string& parent, const std::string& select,
                      const std::string& chain = "[]", const std::string& extra = "") {
  std::string text = R"({"name": ")" + name + "\"";
  if (!parent.empty()) text += R"(, "parent": ")" + parent + "\"";
  return text + R"(, "select": )" + select + R"(, "chain": )" + chain + extra + "}";
}

const std::string kBody =
    component("body", "", "\"all\"", R"([{"deformer": "bend", "param": "body_m"}])");

// Selector: x <= x_max in the parent's local frame.
std::string box_below(double x_max) {
  std::ostringstream text;
  text << R"({"box": {"min": [-100, -100, -100], "max": [)" << x_max << ", 100, 100]}}";
  return text.str();
}

std::string indices_json(const VertexSet& indices) {
  std::string text = R"({"indices": [)";
  for (std::size_t i = 0; i < indices.size(); ++i) {
    text += (i ? ", " : "") + std::to_string(indices[i]);
  }
  return text + "]}";
}

Rig resolve(const std::string& text, const Mesh& mesh = fish()) {
  return resolve_rig(parse_rig_json(text), mesh);
}

std::size_t index_of(const Rig& rig, const std::string& name) {
  for (std::size_t i = 0; i < rig.components.size(); ++i) {
    if (rig.components[i].name == name) return i;
  }
  ADD_FAILURE() << "no component " << name;
  return 0;
}

// The vertices of component k's subtree (itself and its descendants), sorted.
VertexSet subtree_vertices(const Rig& rig, std::size_t k) {
  VertexSet set;
  for (std::size_t c = k; c < rig.subtree_end[k]; ++c) {
    set.insert(set.end(), rig.components[c].vertices.begin(), rig.components[c].vertices.end());
  }
  std::sort(set.begin(), set.end());
  return set;
}

VertexSet vertices_where(const Mesh& mesh, const std::function<bool(const glm::dvec3&)>& keep) {
  VertexSet set;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (keep(glm::dvec3(mesh.positions[v]))) set.push_back(static_cast<std::uint32_t>(v));
  }
  return set;
}

// Checks the structural invariants of a resolved rig: depth-first order with
// contiguous subtrees, own vertex sets ascending, disjoint and covering the mesh,
// children inside their parents, valid frames, stage frames = component frames, x_max
// = the largest |local x| of the subtree, param indices in range.
void expect_consistent(const Rig& rig, const Mesh& mesh) {
  const std::size_t n = rig.components.size();
  ASSERT_EQ(rig.subtree_end.size(), n);
  ASSERT_GT(n, 0u);
  EXPECT_EQ(rig.components[0].parent, -1);
  EXPECT_EQ(rig.subtree_end[0], n);
  std::vector<int> owner(mesh.vertex_count(), -1);
  for (std::size_t k = 0; k < n; ++k) {
    const RigComponent& c = rig.components[k];
    if (k > 0) {
      ASSERT_GE(c.parent, 0);
      const auto p = static_cast<std::size_t>(c.parent);
      EXPECT_LT(p, k) << c.name;
      EXPECT_LE(rig.subtree_end[k], rig.subtree_end[p]) << c.name;  // nested in the parent's
    }
    for (std::size_t d = k + 1; d < rig.subtree_end[k]; ++d) {  // descendants
      EXPECT_GE(rig.depth(d), rig.depth(k) + 1) << rig.components[d].name;
    }
    EXPECT_TRUE(std::is_sorted(c.vertices.begin(), c.vertices.end())) << c.name;
    for (const std::uint32_t v : c.vertices) {
      ASSERT_LT(v, mesh.vertex_count());
      EXPECT_EQ(owner[v], -1) << "vertex " << v << " in two components";
      owner[v] = static_cast<int>(k);
    }
    EXPECT_NO_THROW(c.frame.validate()) << c.name;
    const VertexSet subtree = subtree_vertices(rig, k);
    double x_max = 0.0;
    for (const std::uint32_t v : subtree) {
      x_max = std::max(x_max, std::abs(c.frame.point_to_local(glm::dvec3(mesh.positions[v])).x));
    }
    for (const RigStage& stage : c.chain) {
      EXPECT_EQ(stage.frame.origin, c.frame.origin) << c.name;
      EXPECT_EQ(stage.frame.axis_x, c.frame.axis_x) << c.name;
      EXPECT_EQ(stage.frame.length, c.frame.length) << c.name;
      EXPECT_DOUBLE_EQ(stage.geometry.x_max, x_max) << c.name;
      EXPECT_LT(stage.param, rig.parameters.size()) << c.name;
    }
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << "vertices in no component";
}

// An OBJ file of `mesh` (positions exact to float), its triangles grouped by `group_of`
// (one "g" line per run of equal names) in the order: all triangles of the first name
// first, and so on.
void write_grouped_obj(const std::string& path, const Mesh& mesh,
                       const std::function<std::string(const glm::dvec3&)>& group_of,
                       const std::vector<std::string>& names) {
  std::ofstream out(path);
  out.precision(9);
  for (const glm::vec3& p : mesh.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const std::string& name : names) {
    out << "g " << name << '\n';
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      glm::dvec3 centre(0.0);
      for (int k = 0; k < 3; ++k) centre += glm::dvec3(mesh.positions[mesh.indices[3 * t + k]]);
      if (group_of(centre / 3.0) != name) continue;
      out << "f " << mesh.indices[3 * t] + 1 << ' ' << mesh.indices[3 * t + 1] + 1 << ' '
          << mesh.indices[3 * t + 2] + 1 << '\n';
    }
  }
  ASSERT_TRUE(out.good()) << path;
}

// ---------------------------------------------------------------------------------
// Parsing: every field

TEST(ParseRig, ReadsEveryField) {
  const RigSpec spec = parse_rig_json(R"({
    "frame": {"origin": [1, 2, 3], "x": [0, 0, 2], "y": [0, 1, 0], "length": 1.5},
    "components": [
      {"name": "body", "select": "all",
       "chain": [{"deformer": "bend", "mode": "paper", "param": "body_m"},
                 {"deformer": "bend", "mode": "exact", "param": "turn"}]},
      {"name": "tail", "parent": "body",
       "select": {"box": {"min": [-1, -2, -3], "max": [-0.3, 2, 3.5]}},
       "frame": {"mode": "explicit", "origin": [-0.3, 0, 0], "x": [-1, 0, 0], "y": [0, 1, 0],
                 "length": 0.25},
       "chain": [{"deformer": "hinge", "param": "tail_angle", "width": 0.05}]},
      {"name": "fin", "parent": "tail", "select": {"indices": [3, 1, 4294967295]},
       "frame": {"mode": "auto"}, "chain": []},
      {"name": "dorsal", "parent": "body", "select": {"group": "dorsal fin"},
       "frame": {"mode": "identity"}, "chain": [{"deformer": "hinge", "param": "d"}]},
      {"name": "head", "parent": "body",
       "select": {"half_space": {"point": [0.3, 0, 0], "normal": [1, 0.5, 0]}},
       "frame": {"origin": [0.3, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0]},
       "chain": [{"deformer": "bend", "param": "head_m"}]}
    ]})");
  EXPECT_EQ(spec.frame.mode, Mode::kExplicit);
  EXPECT_EQ(spec.frame.origin, glm::dvec3(1, 2, 3));
  EXPECT_EQ(spec.frame.x, glm::dvec3(0, 0, 2));
  EXPECT_EQ(spec.frame.y, glm::dvec3(0, 1, 0));
  EXPECT_EQ(spec.frame.length, 1.5);
  ASSERT_EQ(spec.components.size(), 5u);

  const ComponentSpec& body = spec.components[0];
  EXPECT_EQ(body.name, "body");
  EXPECT_EQ(body.parent, "");
  EXPECT_EQ(body.select.kind, Kind::kAll);
  EXPECT_FALSE(body.frame.has_value());
  ASSERT_EQ(body.chain.size(), 2u);
  EXPECT_EQ(body.chain[0].deformer, find_deformer_type("bend"));
  EXPECT_EQ(body.chain[0].options[0], 0.0);  // mode paper
  EXPECT_EQ(body.chain[0].param, "body_m");
  EXPECT_EQ(body.chain[1].options[0], 1.0);  // mode exact
  EXPECT_EQ(body.chain[1].param, "turn");

  const ComponentSpec& tail = spec.components[1];
  EXPECT_EQ(tail.parent, "body");
  EXPECT_EQ(tail.select.kind, Kind::kBox);
  EXPECT_EQ(tail.select.box_min, glm::dvec3(-1, -2, -3));
  EXPECT_EQ(tail.select.box_max, glm::dvec3(-0.3, 2, 3.5));
  ASSERT_TRUE(tail.frame.has_value());
  EXPECT_EQ(tail.frame->mode, Mode::kExplicit);
  EXPECT_EQ(tail.frame->origin, glm::dvec3(-0.3, 0, 0));
  EXPECT_EQ(tail.frame->x, glm::dvec3(-1, 0, 0));
  EXPECT_EQ(tail.frame->length, 0.25);
  ASSERT_EQ(tail.chain.size(), 1u);
  EXPECT_EQ(tail.chain[0].deformer, find_deformer_type("hinge"));
  EXPECT_EQ(tail.chain[0].options[0], 0.05);  // width
  EXPECT_EQ(tail.chain[0].param, "tail_angle");

  const ComponentSpec& fin = spec.components[2];
  EXPECT_EQ(fin.parent, "tail");
  EXPECT_EQ(fin.select.kind, Kind::kIndices);
  EXPECT_EQ(fin.select.indices, (VertexSet{3, 1, 4294967295u}));
  ASSERT_TRUE(fin.frame.has_value());
  EXPECT_EQ(fin.frame->mode, Mode::kAuto);
  EXPECT_TRUE(fin.chain.empty());

  const ComponentSpec& dorsal = spec.components[3];
  EXPECT_EQ(dorsal.select.kind, Kind::kGroup);
  EXPECT_EQ(dorsal.select.group, "dorsal fin");
  EXPECT_EQ(dorsal.frame->mode, Mode::kIdentity);
  EXPECT_EQ(dorsal.chain[0].options[0], 0.0);  // hinge width default

  const ComponentSpec& head = spec.components[4];
  EXPECT_EQ(head.select.kind, Kind::kHalfSpace);
  EXPECT_EQ(head.select.point, glm::dvec3(0.3, 0, 0));
  EXPECT_EQ(head.select.normal, glm::dvec3(1, 0.5, 0));
  EXPECT_EQ(head.frame->mode, Mode::kExplicit);
  EXPECT_FALSE(head.frame->length.has_value());
  EXPECT_EQ(head.chain[0].options[0], 1.0);  // bend mode default: exact
}

TEST(ParseRig, DefaultsAndTheOtherFrameModes) {
  const RigSpec automatic = parse_rig_json(R"({"components": [
      {"name": "body", "select": "all", "chain": []}]})");
  EXPECT_EQ(automatic.frame.mode, Mode::kAuto);
  EXPECT_EQ(parse_rig_json(rig_text(kBody, R"({"mode": "auto"})")).frame.mode, Mode::kAuto);
  EXPECT_EQ(parse_rig_json(rig_text(kBody, R"({"mode": "identity"})")).frame.mode, Mode::kIdentity);
  const RigSpec explicit_frame = parse_rig_json(rig_text(
      kBody, R"({"mode": "explicit", "origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 0, 1]})"));
  EXPECT_EQ(explicit_frame.frame.mode, Mode::kExplicit);
  EXPECT_EQ(explicit_frame.frame.y, glm::dvec3(0, 0, 1));
  EXPECT_FALSE(explicit_frame.frame.length.has_value());
}

// ---------------------------------------------------------------------------------
// Parsing: errors

TEST(ParseRigErrors, MalformedJsonIsAFormatErrorWithThePosition) {
  EXPECT_TRUE(Fails([] { parse_rig_json("{\"components\": [\n  {\"name\": \"body\",,}]}"); },
                    ErrorCode::kFormat, "rig", "line 2, column"));
  EXPECT_TRUE(Fails([] { parse_rig_json(""); }, ErrorCode::kFormat, "rig", "malformed JSON"));
  EXPECT_TRUE(Fails([] { parse_rig_json(rig_text(kBody) + " trailing"); }, ErrorCode::kFormat,
                    "rig", "malformed JSON"));
  EXPECT_TRUE(Fails(
      [] {
        parse_rig_json(rig_text(kBody, R"({"origin": [0, 0, 0], "x": [1e999, 0, 0],
                                                           "y": [0, 1, 0]})"));
      },
      ErrorCode::kFormat, "rig", "1e999"));
}

struct ParseCase {
  std::string text;
  std::string field;
  std::string message_part;
};

std::ostream& operator<<(std::ostream& out, const ParseCase& c) { return out << c.field; }

class ParseRigInvalid : public ::testing::TestWithParam<ParseCase> {};

TEST_P(ParseRigInvalid, NamesTheFieldTheValueAndWhatWasExpected) {
  const ParseCase& c = GetParam();
  EXPECT_TRUE(
      Fails([&] { parse_rig_json(c.text); }, ErrorCode::kInvalidArgument, c.field, c.message_part))
      << c.text;
}

const std::string kTail = "components[1] 'tail'";

// A rig whose second component, "tail", has `select`, `chain` and `extra`.
std::string with_tail(const std::string& select, const std::string& chain = "[]",
                      const std::string& extra = "") {
  return rig_text(kBody + ", " + component("tail", "body", select, chain, extra));
}

std::string with_tail_stage(const std::string& stage) {
  return with_tail("\"all\"", "[" + stage + "]");
}

std::string with_tail_frame(const std::string& frame) {
  return with_tail("\"all\"", "[]", R"(, "frame": )" + frame);
}

const ParseCase kParseCases[] = {
    // The document.
    {"[]", "rig", "expected an object"},
    {R"({"components": [], "colour": 1})", "colour", "unknown key 'colour'"},
    {R"({"frame": {"mode": "auto"}})", "components", "missing"},
    {R"({"components": {"name": "body"}})", "components", "expected an array"},
    {R"({"components": [1]})", "components[0]", "expected an object"},
    {R"({"frame": "auto", "components": []})", "frame", "expected an object"},
    {R"({"frame": {"origin": [0, 0, 0], "x": [1, 0, 0]}, "components": []})", "frame.y", "missing"},
    {R"({"frame": {"mode": "automatic"}, "components": []})", "frame.mode",
     "\"auto\", \"identity\" or \"explicit\""},
    {R"({"frame": {"mode": 1}, "components": []})", "frame.mode", "= 1"},
    // Components.
    {R"({"components": [{"select": "all", "chain": []}]})", "components[0].name", "missing"},
    {R"({"components": [{"name": "", "select": "all", "chain": []}]})", "components[0].name",
     "non-empty string"},
    {R"({"components": [{"name": 7, "select": "all", "chain": []}]})", "components[0].name", "= 7"},
    {R"({"components": [{"name": "body", "select": "all", "chian": []}]})",
     "components[0] 'body'.chian", "unknown key 'chian'"},
    {R"({"components": [{"name": "body", "select": "all"}]})", "components[0] 'body'.chain",
     "missing"},
    {R"({"components": [{"name": "body", "select": "all", "chain": {}}]})",
     "components[0] 'body'.chain", "expected an array"},
    {R"({"components": [{"name": "body", "chain": []}]})", "components[0] 'body'.select",
     "missing"},
    {R"({"components": [{"name": "body", "select": "all", "chain": [],
                         "frame": {"mode": "auto"}}]})",
     "components[0] 'body'.frame", "root component takes no frame"},
    {rig_text(kBody + R"(, {"name": "tail", "parent": "", "select": "all", "chain": []})"),
     kTail + ".parent", "non-empty string"},
    {rig_text(kBody + R"(, {"name": "tail", "parent": 0, "select": "all", "chain": []})"),
     kTail + ".parent", "= 0"},
    {R"({"components": [{"name": "body", "name": "b", "select": "all", "chain": []}]})",
     "components[0].name", "duplicate key 'name'"},
    {R"({"components": [{"name": "body", "select": "all",
                         "chain": [{"deformer": "bend", "param": "a", "param": "b"}]}]})",
     "components[0].chain[0].param", "duplicate key 'param'"},
    // Selectors.
    {with_tail("\"everything\""), kTail + ".select", "\"all\" or an object"},
    {with_tail("3"), kTail + ".select", "= 3"},
    {with_tail("{}"), kTail + ".select", "\"all\" or an object"},
    {with_tail(R"({"sphere": {"radius": 1}})"), kTail + ".select.sphere", "unknown key 'sphere'"},
    {with_tail(R"({"group": "a", "indices": [1]})"), kTail + ".select", "not several"},
    {with_tail(R"({"indices": 3})"), kTail + ".select.indices", "array of vertex indices"},
    {with_tail(R"({"indices": [0, -1]})"), kTail + ".select.indices[1]", "= -1"},
    {with_tail(R"({"indices": [1.5]})"), kTail + ".select.indices[0]", "a vertex index"},
    {with_tail(R"({"indices": [4294967296]})"), kTail + ".select.indices[0]", "a vertex index"},
    {with_tail(R"({"group": ""})"), kTail + ".select.group", "non-empty string"},
    {with_tail(R"({"group": ["fin"]})"), kTail + ".select.group", "[\"fin\"]"},
    {with_tail(R"({"box": [0, 1]})"), kTail + ".select.box", "expected an object"},
    {with_tail(R"({"box": {"min": [0, 0, 0]}})"), kTail + ".select.box.max", "missing"},
    {with_tail(R"({"box": {"min": [1, 2], "max": [3, 4, 5]}})"), kTail + ".select.box.min",
     "= [1,2]: expected an array of 3 finite numbers"},
    {with_tail(R"({"box": {"min": [0, "0", 0], "max": [3, 4, 5]}})"), kTail + ".select.box.min",
     "array of 3 finite numbers"},
    {with_tail(R"({"box": {"min": [0, 0, 0], "max": [1, -1, 1]}})"), kTail + ".select.box.max",
     "max >= min"},
    {with_tail(R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1], "mid": [0, 0, 0]}})"),
     kTail + ".select.box.mid", "unknown key 'mid'"},
    {with_tail(R"({"half_space": {"point": [0, 0, 0]}})"), kTail + ".select.half_space.normal",
     "missing"},
    {with_tail(R"({"half_space": {"point": [0, 0, 0], "normal": [1, 0, 0], "offset": 1}})"),
     kTail + ".select.half_space.offset", "unknown key 'offset'"},
    // Child frames.
    {with_tail_frame(R"({"mode": "automatic"})"), kTail + ".frame.mode",
     "\"auto\", \"identity\" or \"explicit\""},
    {with_tail_frame(R"({"mode": "auto", "origin": [0, 0, 0]})"), kTail + ".frame.origin",
     "unexpected with mode 'auto'"},
    {with_tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0]})"), kTail + ".frame.y", "missing"},
    {with_tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0], "length": 0})"),
     kTail + ".frame.length", "= 0: expected a finite number > 0"},
    {with_tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0], "length": -2})"),
     kTail + ".frame.length", "= -2"},
    {with_tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0], "length": "1"})"),
     kTail + ".frame.length", "> 0"},
    {with_tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0], "z": [0, 0, 1]})"),
     kTail + ".frame.z", "unknown key 'z'"},
    {with_tail_frame("[]"), kTail + ".frame", "expected an object"},
    // Stages.
    {with_tail("\"all\"", "[1]"), kTail + ".chain[0]", "expected an object"},
    {with_tail_stage(R"({"param": "a"})"), kTail + ".chain[0].deformer", "missing"},
    {with_tail_stage(R"({"deformer": "twist", "param": "a"})"), kTail + ".chain[0].deformer",
     "= \"twist\": expected " + deformer_type_names()},
    {with_tail_stage(R"({"deformer": "bend", "mode": "approximate", "param": "a"})"),
     kTail + ".chain[0].mode", "\"paper\" or \"exact\""},
    {with_tail_stage(R"({"deformer": "hinge", "mode": "exact", "param": "a"})"),
     kTail + ".chain[0].mode", "bend only"},
    {with_tail_stage(R"({"deformer": "bend", "width": 0.1, "param": "a"})"),
     kTail + ".chain[0].width", "hinge only"},
    {with_tail_stage(R"({"deformer": "hinge", "width": -0.1, "param": "a"})"),
     kTail + ".chain[0].width", "= -0.1: expected a finite number >= 0"},
    {with_tail_stage(R"({"deformer": "hinge", "width": "wide", "param": "a"})"),
     kTail + ".chain[0].width", ">= 0"},
    {with_tail_stage(R"({"deformer": "hinge"})"), kTail + ".chain[0].param", "missing"},
    {with_tail_stage(R"({"deformer": "hinge", "param": ""})"), kTail + ".chain[0].param",
     "non-empty string"},
    {with_tail_stage(R"({"deformer": "hinge", "param": 2})"), kTail + ".chain[0].param", "= 2"},
    {with_tail_stage(R"({"deformer": "hinge", "param": "a", "angle": 1})"),
     kTail + ".chain[0].angle", "unknown key 'angle'"},
};

INSTANTIATE_TEST_SUITE_P(Cases, ParseRigInvalid, ::testing::ValuesIn(kParseCases));

TEST(ParseRigErrors, TopLevelUnknownKeyAndMessagesQuoteLongValuesShortened) {
  std::string long_name(500, 'x');
  EXPECT_TRUE(Fails([&] { parse_rig_json(with_tail(R"({"group": [")" + long_name + "\"]}")); },
                    ErrorCode::kInvalidArgument, kTail + ".select.group", "xxx..."));
}

TEST(LoadRigFile, ReadsAFileAndPutsThePathInFrontOfErrors) {
  const std::string path = test::temp_path("rig.json");
  {
    std::ofstream out(path);
    out << with_tail(box_below(-0.3));
  }
  const RigSpec spec = load_rig_file(path);
  ASSERT_EQ(spec.components.size(), 2u);
  EXPECT_EQ(spec.components[1].select.kind, Kind::kBox);

  const std::string bad = test::temp_path("bad.json");
  {
    std::ofstream out(bad);
    out << with_tail("\"none\"");
  }
  try {
    load_rig_file(bad);
    ADD_FAILURE() << "nothing thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), kTail + ".select");
    EXPECT_EQ(std::string(e.what()).rfind("'" + bad + "': " + kTail + ".select", 0), 0u)
        << e.what();
  }
  const std::string missing = test::temp_path("missing.json");
  EXPECT_TRUE(Fails([&] { load_rig_file(missing); }, ErrorCode::kIo, "path", "cannot open"));
  const std::string folder = test::temp_path("folder.json");
  std::filesystem::create_directory(folder);
  EXPECT_TRUE(Fails([&] { load_rig_file(folder); }, ErrorCode::kIo, "path", "directory"));
  const std::string empty = test::temp_path("empty.json");
  std::ofstream{empty};
  EXPECT_TRUE(Fails([&] { load_rig_file(empty); }, ErrorCode::kFormat, "rig", "malformed JSON"));
}

// ---------------------------------------------------------------------------------
// Resolving: the tree, vertex sets, stages

// body -> tail (x <= -0.3) -> fin (the tail's end); body -> head (x > 0.3); listed
// out of depth-first order: body, tail, head, fin.
std::string body_tail_fin_head() {
  return rig_text(
      kBody + ", " +
      component("tail", "body", box_below(-0.3),
                R"([{"deformer": "hinge", "param": "tail_angle", "width": 0.05}])") +
      ", " +
      component("head", "body", R"({"half_space": {"point": [0.3, 0, 0], "normal": [1, 0, 0]}})",
                R"([{"deformer": "bend", "param": "body_m"},
                    {"deformer": "hinge", "param": "head_angle"}])") +
      ", " +
      component("fin", "tail", R"({"box": {"min": [0.7, -100, -100], "max": [100, 100, 100]}})",
                R"([{"deformer": "hinge", "param": "fin_angle"}])"));
}

TEST(ResolveRig, HierarchyOnTheSyntheticFish) {
  const Rig rig = resolve(body_tail_fin_head());
  ASSERT_EQ(rig.components.size(), 4u);
  expect_consistent(rig, fish());

  // Depth-first order, parents, subtrees.
  std::vector<std::string> names;
  for (const RigComponent& c : rig.components) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"body", "tail", "fin", "head"}));
  EXPECT_EQ(rig.components[1].parent, 0);
  EXPECT_EQ(rig.components[2].parent, 1);
  EXPECT_EQ(rig.components[3].parent, 0);
  EXPECT_EQ(rig.subtree_end, (std::vector<std::size_t>{4, 3, 3, 4}));

  // Parameters in order of first use in the file (head before fin), indices shared.
  EXPECT_EQ(parameter_names(rig),
            (std::vector<std::string>{"body_m", "tail_angle", "head_angle", "fin_angle"}));
  EXPECT_EQ(rig.param_index("fin_angle"), 3u);
  EXPECT_TRUE(Fails([&] { rig.param_index("tail"); }, ErrorCode::kInvalidArgument, "tail",
                    "not a parameter of the rig (its parameters: body_m, tail_angle"));
  EXPECT_EQ(rig.components[0].chain[0].param, 0u);
  EXPECT_EQ(rig.components[3].chain[0].param, 0u);  // head reuses body_m
  EXPECT_EQ(rig.components[3].chain[1].param, 2u);
  EXPECT_EQ(rig.components[2].chain[0].param, 3u);
  EXPECT_EQ(rig.components[1].chain[0].deformer, find_deformer_type("hinge"));
  EXPECT_EQ(rig.components[1].chain[0].options[0], 0.05);  // width
  EXPECT_EQ(rig.components[0].chain[0].options[0], 1.0);   // mode exact

  // Vertex sets: the tail's subtree is x <= -0.3, the fin its outer part, the head
  // x > 0.3; own = subtree minus children.
  const VertexSet tail_subtree =
      vertices_where(fish(), [](const glm::dvec3& p) { return p.x <= -0.3; });
  EXPECT_EQ(subtree_vertices(rig, 1), tail_subtree);
  const VertexSet head = vertices_where(fish(), [](const glm::dvec3& p) { return p.x > 0.3; });
  EXPECT_EQ(rig.components[3].vertices, head);
  const VertexSet& fin = rig.components[2].vertices;
  ASSERT_FALSE(fin.empty());
  const BodyFrame& tail_frame = rig.components[1].frame;
  for (const std::uint32_t v : tail_subtree) {
    const bool in_fin = std::binary_search(fin.begin(), fin.end(), v);
    EXPECT_EQ(in_fin, tail_frame.point_to_local(glm::dvec3(fish().positions[v])).x >= 0.7) << v;
  }
  EXPECT_EQ(rig.components[1].vertices.size() + fin.size(), tail_subtree.size());
  EXPECT_EQ(rig.components[0].vertices.size() + tail_subtree.size() + head.size(),
            fish().vertex_count());

  // x_max: the body in the identity frame reaches 0.5; the tail's auto frame spans
  // its subtree from the seam (0) to the tip (1), the fin included.
  EXPECT_NEAR(rig.components[0].chain[0].geometry.x_max, 0.5, 1e-7);
  EXPECT_NEAR(rig.components[1].chain[0].geometry.x_max, 1.0, 1e-9);
  EXPECT_NEAR(rig.components[3].chain[1].geometry.x_max, 1.0, 1e-9);

  // Paths, bottom-up.
  using Path = std::vector<StageRef>;
  EXPECT_EQ(rig.path(2), (Path{{2, 0}, {1, 0}, {0, 0}}));
  EXPECT_EQ(rig.path(3), (Path{{3, 0}, {3, 1}, {0, 0}}));
  EXPECT_EQ(rig.path(0), (Path{{0, 0}}));
  EXPECT_EQ(rig.depth(2), 2u);
  EXPECT_TRUE(
      Fails([&] { rig.path(4); }, ErrorCode::kInvalidArgument, "component", "out of range"));
  EXPECT_TRUE(
      Fails([&] { rig.depth(9); }, ErrorCode::kInvalidArgument, "component", "out of range"));
}

TEST(ResolveRig, DepthFourTreePathsAndDepths) {
  // Listed leaf first: c in b in a in body, nested index ranges; c has no stages.
  auto first = [](std::uint32_t n) {
    VertexSet set(n);
    for (std::uint32_t v = 0; v < n; ++v) set[v] = v;
    return set;
  };
  const std::string text = rig_text(
      component("c", "b", indices_json(first(200))) + ", " +
      component(
          "b", "a", indices_json(first(400)),
          R"([{"deformer": "hinge", "param": "p_b"}, {"deformer": "bend", "param": "p_b2"}])") +
      ", " +
      component("a", "body", indices_json(first(800)),
                R"([{"deformer": "hinge", "param": "p_a"}])") +
      ", " + component("body", "", "\"all\"", R"([{"deformer": "bend", "param": "m"}])"));
  const Rig rig = resolve(text);
  expect_consistent(rig, fish());
  ASSERT_EQ(rig.components.size(), 4u);
  const std::vector<std::string> names = {"body", "a", "b", "c"};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(rig.components[k].name, names[k]);
    EXPECT_EQ(rig.depth(k), k);
    EXPECT_EQ(rig.subtree_end[k], 4u);
    EXPECT_EQ(rig.components[k].parent, static_cast<int>(k) - 1);
  }
  EXPECT_EQ(parameter_names(rig), (std::vector<std::string>{"p_b", "p_b2", "p_a", "m"}));
  using Path = std::vector<StageRef>;
  EXPECT_EQ(rig.path(3), (Path{{2, 0}, {2, 1}, {1, 0}, {0, 0}}));
  EXPECT_EQ(rig.path(2), (Path{{2, 0}, {2, 1}, {1, 0}, {0, 0}}));
  EXPECT_EQ(rig.path(1), (Path{{1, 0}, {0, 0}}));
  EXPECT_EQ(rig.components[3].vertices, first(200));
  EXPECT_EQ(rig.components[2].vertices.size(), 200u);
  EXPECT_EQ(rig.components[2].vertices.front(), 200u);
  EXPECT_EQ(rig.components[0].vertices.front(), 800u);
  EXPECT_EQ(rig.components[2].chain[1].param, 1u);
  EXPECT_EQ(rig.components[1].chain[0].param, 2u);
}

TEST(ResolveRig, BlubBodyTailAndFinWithTheAutomaticBodyFrame) {
  const Mesh& mesh = blub();
  const std::string text = rig_text(
      kBody + ", " +
          component("tail", "body", box_below(-0.3),
                    R"([{"deformer": "bend", "mode": "paper", "param": "tail_m"}])") +
          ", " +
          component("fin", "tail", R"({"box": {"min": [0.5, -100, -100], "max": [100, 100, 100]}})",
                    R"([{"deformer": "hinge", "param": "fin_angle", "width": 0.1}])") +
          ", " +
          component("pectoral", "body",
                    R"({"half_space": {"point": [0.2, 0, 0], "normal": [1, 0, 0]}})"),
      R"({"mode": "auto"})");
  const Rig rig = resolve(text, mesh);
  ASSERT_EQ(rig.components.size(), 4u);
  expect_consistent(rig, mesh);
  const BodyFrame body = find_body_frame(mesh);
  EXPECT_EQ(rig.components[0].frame.origin, body.origin);
  EXPECT_EQ(rig.components[0].frame.axis_x, body.axis_x);

  const std::size_t tail = index_of(rig, "tail");
  const std::size_t fin = index_of(rig, "fin");
  EXPECT_EQ(tail, 1u);
  EXPECT_EQ(fin, 2u);
  for (const std::uint32_t v : subtree_vertices(rig, tail)) {
    EXPECT_LE(body.point_to_local(glm::dvec3(mesh.positions[v])).x, -0.3);
  }
  // The tail's automatic frame: attached at the cut, pointing to the tail end.
  const BodyFrame& tail_frame = rig.components[tail].frame;
  const glm::dvec3 seam = body.point_to_local(tail_frame.origin);
  EXPECT_NEAR(seam.x, -0.3, 0.03);
  EXPECT_LT(glm::dot(tail_frame.axis_x, body.axis_x), -0.8);
  EXPECT_GT(glm::dot(tail_frame.axis_y, body.axis_y), 0.5);
  EXPECT_FALSE(rig.components[fin].vertices.empty());
  EXPECT_FALSE(rig.components[tail].vertices.empty());
}

// ---------------------------------------------------------------------------------
// Resolving: frames

TEST(ResolveRig, AutoChildFrameAttachesAtTheSeam) {
  const Rig rig = resolve(with_tail(box_below(-0.3)));
  const BodyFrame& frame = rig.components[1].frame;
  // The seam is the last ring at x <= -0.3 (x = -0.5 + 9/47), centred on the spine.
  const double seam_x = -0.5 + 9.0 / 47.0;
  EXPECT_TRUE(Near(frame.origin, glm::dvec3(seam_x, 0, 0), 1e-6));
  EXPECT_TRUE(Near(frame.axis_x, glm::dvec3(-1, 0, 0), 1e-6));
  EXPECT_TRUE(Near(frame.axis_y, glm::dvec3(0, 1, 0), 1e-6));
  EXPECT_TRUE(Near(frame.axis_z, glm::dvec3(0, 0, -1), 1e-6));
  EXPECT_NEAR(frame.length, seam_x + 0.5, 1e-6);  // to the tail's tip at x = -0.5
}

TEST(ResolveRig, AutoFrameOfASeparatePieceStartsAtItsVertexNearestTheParentOrigin) {
  // The fish plus a separate tetrahedron above its back (no shared triangle).
  Mesh mesh = fish();
  const auto base = static_cast<std::uint32_t>(mesh.vertex_count());
  mesh.positions.insert(
      mesh.positions.end(),
      {{0.0f, 0.2f, 0.0f}, {0.1f, 0.35f, 0.0f}, {-0.1f, 0.35f, 0.05f}, {0.0f, 0.35f, -0.05f}});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3, base,
                                           base + 3, base + 1, base + 1, base + 3, base + 2});
  compute_vertex_normals(mesh);
  const Rig rig = resolve(
      rig_text(kBody + ", " +
               component("fin", "body", indices_json({base, base + 1, base + 2, base + 3}))),
      mesh);
  const BodyFrame& frame = rig.components[1].frame;
  EXPECT_TRUE(Near(frame.origin, glm::dvec3(mesh.positions[base]), 1e-9));
  EXPECT_GT(frame.axis_x.y, 0.9);                   // upwards, to the centroid
  EXPECT_NEAR(std::abs(frame.axis_y.z), 1.0, 0.2);  // the parent's z: y was parallel
  EXPECT_NEAR(glm::dot(frame.axis_x, frame.axis_y), 0.0, 1e-12);
  EXPECT_NEAR(frame.length, 0.15, 1e-6);
}

TEST(ResolveRig, ChildExplicitFrameIsWrittenInTheParentsLocalFrame) {
  // Parent: origin (1, 0, 0), length 2, axes of the mesh.
  const std::string parent_frame =
      R"({"origin": [1, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0], "length": 2})";
  const std::string child_frame =
      R"(, "frame": {"origin": [0.25, 0, 0], "x": [0, 3, 0], "y": [-1, 1, 0], "length": 0.5})";
  const std::string text = rig_text(
      kBody + ", " + component("tail", "body", box_below(-0.6), "[]", child_frame), parent_frame);
  const Rig rig = resolve(text);
  EXPECT_TRUE(Near(rig.components[0].frame.origin, glm::dvec3(1, 0, 0), 0.0));
  EXPECT_EQ(rig.components[0].frame.length, 2.0);
  const BodyFrame& tail = rig.components[1].frame;
  EXPECT_TRUE(Near(tail.origin, glm::dvec3(1.5, 0, 0), 1e-12));
  EXPECT_TRUE(Near(tail.axis_x, glm::dvec3(0, 1, 0), 1e-12));
  EXPECT_TRUE(Near(tail.axis_y, glm::dvec3(-1, 0, 0), 1e-12));  // Gram-Schmidt
  EXPECT_TRUE(Near(tail.axis_z, glm::dvec3(0, 0, 1), 1e-12));
  EXPECT_DOUBLE_EQ(tail.length, 1.0);
  // The box is in the parent's local frame: x_local = (x - 1) / 2 <= -0.6, x <= -0.2.
  EXPECT_EQ(subtree_vertices(rig, 1),
            vertices_where(fish(), [](const glm::dvec3& p) { return (p.x - 1.0) / 2.0 <= -0.6; }));

  // A rotated parent: x along mesh z, y along mesh y (z = -mesh x).
  const Rig rotated = resolve(rig_text(
      kBody + ", " +
          component("tail", "body", "\"all\"", "[]",
                    R"(, "frame": {"origin": [0.25, 0.1, 0], "x": [0, 1, 0], "y": [1, 0, 0]})"),
      R"({"origin": [1, 0, 0], "x": [0, 0, 1], "y": [0, 1, 0], "length": 2})"));
  const BodyFrame& turned = rotated.components[1].frame;
  EXPECT_TRUE(Near(turned.origin, glm::dvec3(1, 0.2, 0.5), 1e-12));
  EXPECT_TRUE(Near(turned.axis_x, glm::dvec3(0, 1, 0), 1e-12));
  EXPECT_TRUE(Near(turned.axis_y, glm::dvec3(0, 0, 1), 1e-12));
  // No length: the extent of the (whole) fish along mesh y.
  double lo = 1e9, hi = -1e9;
  for (const glm::vec3& p : fish().positions) {
    lo = std::min(lo, static_cast<double>(p.y));
    hi = std::max(hi, static_cast<double>(p.y));
  }
  EXPECT_NEAR(turned.length, hi - lo, 1e-12);
  EXPECT_TRUE(rotated.components[0].vertices.empty());  // the child took "all"
  // An identity child frame is its parent's.
  const Rig same = resolve(rig_text(
      kBody + ", " +
          component("tail", "body", box_below(-0.6), "[]", R"(, "frame": {"mode": "identity"})"),
      parent_frame));
  EXPECT_EQ(same.components[1].frame.origin, same.components[0].frame.origin);
  EXPECT_EQ(same.components[1].frame.length, 2.0);
}

TEST(ResolveRig, ChildFramesFollowARigidMotionOfTheMeshAndTheRootFrame) {
  const glm::dquat q = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1, 2, -0.5)));
  const glm::dvec3 t(0.3, -1.2, 2.0);
  auto move = [&](const glm::dvec3& p) { return q * p + t; };
  auto vec = [](const glm::dvec3& v) {
    std::ostringstream out;
    out.precision(17);
    out << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return out.str();
  };
  auto rig_for = [&](const glm::dvec3& origin, const glm::dvec3& x, const glm::dvec3& y) {
    return rig_text(
        kBody + ", " +
            component("tail", "body", box_below(-0.3), "[]",
                      R"(, "frame": {"origin": [-0.3, 0.01, 0], "x": [-1, 0.2, 0],)"
                      R"( "y": [0, 1, 0], "length": 0.2})") +
            ", " +
            component("head", "body",
                      R"({"half_space": {"point": [0.3, 0, 0], "normal": [1, 0, 0]}})") +
            ", " + component("fin", "tail", box_below(0.5)),
        R"({"origin": )" + vec(origin) + R"(, "x": )" + vec(x) + R"(, "y": )" + vec(y) + "}");
  };
  const glm::dvec3 origin(0.05, 0.0, 0.0), x(1, 0.1, 0), y(0, 1, 0.2);
  const Rig rest = resolve(rig_for(origin, x, y));
  Mesh moved = fish();
  for (glm::vec3& p : moved.positions) p = glm::vec3(move(glm::dvec3(p)));
  const Rig after = resolve(rig_for(move(origin), q * x, q * y), moved);
  ASSERT_EQ(after.components.size(), rest.components.size());
  // The moved positions are rounded to float (~2e-7 here): automatic frames, taken
  // from vertices a few centimetres apart, turn by up to ~2e-5.
  for (std::size_t k = 0; k < rest.components.size(); ++k) {
    const BodyFrame& a = rest.components[k].frame;
    const BodyFrame& b = after.components[k].frame;
    const std::string& name = rest.components[k].name;
    EXPECT_TRUE(Near(b.origin, move(a.origin), 1e-5)) << name;
    EXPECT_TRUE(Near(b.axis_x, q * a.axis_x, 1e-4)) << name;
    EXPECT_TRUE(Near(b.axis_y, q * a.axis_y, 1e-4)) << name;
    EXPECT_TRUE(Near(b.axis_z, q * a.axis_z, 1e-4)) << name;
    EXPECT_NEAR(b.length, a.length, 1e-5) << name;
    EXPECT_EQ(after.components[k].vertices, rest.components[k].vertices) << name;
  }
  // The explicit child frame is the parent's local one converted.
  const BodyFrame& root = rest.components[0].frame;
  EXPECT_TRUE(
      Near(rest.components[1].frame.origin, root.point_to_mesh(glm::dvec3(-0.3, 0.01, 0)), 1e-12));
  EXPECT_NEAR(rest.components[1].frame.length, 0.2 * root.length, 1e-12);
}

// ---------------------------------------------------------------------------------
// Resolving: groups

TEST(ResolveRig, SelectsFaceGroupsOfAnObjWithGroupLines) {
  const std::string path = test::temp_path("grouped_fish.obj");
  auto group_of = [](const glm::dvec3& centre) {
    // "dorsal" stays clear of the tail: the two share no vertex.
    return centre.x < -0.3                     ? std::string("tail")
           : centre.x > 0.0 && centre.y > 0.05 ? "dorsal"
                                               : "trunk";
  };
  write_grouped_obj(path, fish(), group_of, {"trunk", "tail", "dorsal"});
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.positions, fish().positions);
  ASSERT_EQ(mesh.groups.size(), 3u);
  EXPECT_EQ(mesh.groups[1].name, "tail");

  const Rig rig =
      resolve(rig_text(kBody + ", " + component("tail", "body", R"({"group": "tail"})") + ", " +
                       component("top", "body", R"({"group": "dorsal"})")),
              mesh);
  expect_consistent(rig, mesh);
  VertexSet tail;
  const FaceGroup& group = mesh.groups[1];
  for (std::size_t i = 3 * group.first_triangle;
       i < 3 * (group.first_triangle + group.triangle_count); ++i) {
    tail.push_back(mesh.indices[i]);
  }
  std::sort(tail.begin(), tail.end());
  tail.erase(std::unique(tail.begin(), tail.end()), tail.end());
  EXPECT_EQ(rig.components[1].vertices, tail);

  // Overlapping groups (they share the vertices of the triangles between them).
  EXPECT_TRUE(Fails(
      [&] {
        resolve(rig_text(kBody + ", " + component("tail", "body", R"({"group": "tail"})") + ", " +
                         component("trunk", "body", R"({"group": "trunk"})")),
                mesh);
      },
      ErrorCode::kInvalidArgument, "components[2] 'trunk'.select", "sibling 'tail'"));
  // A group reaching outside its parent.
  EXPECT_TRUE(Fails(
      [&] {
        resolve(rig_text(kBody + ", " + component("tail", "body", R"({"group": "tail"})") + ", " +
                         component("fin", "tail", R"({"group": "trunk"})")),
                mesh);
      },
      ErrorCode::kInvalidArgument, "components[2] 'fin'.select.group",
      "outside the parent 'tail'"));
  EXPECT_TRUE(Fails(
      [&] {
        resolve(rig_text(kBody + ", " + component("fin", "body", R"({"group": "fins"})")), mesh);
      },
      ErrorCode::kInvalidArgument, "components[1] 'fin'.select.group",
      "'fins' is not a face group of the mesh (its groups: 'trunk', 'tail', 'dorsal')"));
}

// ---------------------------------------------------------------------------------
// Resolving: errors

struct ResolveCase {
  std::string name;
  std::string text;
  std::string field;
  std::string message_part;
};

std::ostream& operator<<(std::ostream& out, const ResolveCase& c) { return out << c.name; }

class ResolveRigInvalid : public ::testing::TestWithParam<ResolveCase> {};

TEST_P(ResolveRigInvalid, NamesTheComponentTheFieldAndTheProblem) {
  const ResolveCase& c = GetParam();
  EXPECT_TRUE(Fails([&] { resolve(c.text); }, ErrorCode::kInvalidArgument, c.field, c.message_part))
      << c.text;
}

std::string tail_frame(const std::string& frame) {
  return with_tail(box_below(-0.3), "[]", R"(, "frame": )" + frame);
}

const ResolveCase kResolveCases[] = {
    {"NoComponents", R"({"components": []})", "components", "is empty"},
    {"DuplicateName", rig_text(kBody + ", " + component("body", "body", box_below(-0.3))),
     "components[1] 'body'.name", "also the name of components[0]"},
    {"UnknownParent", rig_text(kBody + ", " + component("tail", "bdy", box_below(-0.3))),
     kTail + ".parent", "'bdy' is not a component of the rig (its components: body, tail)"},
    {"TwoRoots", rig_text(kBody + ", " + component("tail", "", box_below(-0.3))), kTail + ".parent",
     "exactly one root"},
    {"NoRoot", rig_text(component("a", "b", "\"all\"") + ", " + component("b", "a", "\"all\"")),
     "components", "no root component"},
    {"Cycle",
     rig_text(kBody + ", " + component("a", "b", box_below(-0.3)) + ", " +
              component("b", "a", box_below(-0.4))),
     "components[1] 'a'.parent", "loops ('a' -> 'b' -> 'a'"},
    {"SelfParent", rig_text(kBody + ", " + component("a", "a", box_below(-0.3))),
     "components[1] 'a'.parent", "loops ('a' -> 'a'"},
    {"CycleBelowATree",
     rig_text(kBody + ", " + component("c", "b", box_below(-0.3)) + ", " +
              component("a", "c", box_below(-0.3)) + ", " + component("b", "a", box_below(-0.3)) +
              ", " + component("d", "c", box_below(-0.3))),
     "components[1] 'c'.parent", "'c' -> 'b' -> 'a' -> 'c'"},
    {"RootNotAll", rig_text(component("body", "", box_below(0.0))), "components[0] 'body'.select",
     "must select \"all\""},
    {"RootWithIndices", rig_text(component("body", "", R"({"indices": [0, 1, 2]})")),
     "components[0] 'body'.select", "must select \"all\""},
    {"OverlappingSiblings",
     rig_text(kBody + ", " + component("tail", "body", box_below(-0.3)) + ", " +
              component("rear", "body", box_below(-0.2))),
     "components[2] 'rear'.select",
     "which its sibling 'tail' (components[1]) also takes: siblings must be disjoint"},
    {"ChildIndexOutsideParent",
     rig_text(kBody + ", " + component("tail", "body", box_below(-0.3)) + ", " +
              component("fin", "tail", R"({"indices": [0, 1473]})")),
     "components[2] 'fin'.select.indices[1]", "vertex 1473 is outside the parent 'tail'"},
    {"IndexOutOfRange", with_tail(R"({"indices": [1474]})"), kTail + ".select.indices[0]",
     "vertex 1474 is out of range (the mesh has 1474 vertices)"},
    {"EmptyBox", with_tail(R"({"box": {"min": [2, 2, 2], "max": [3, 3, 3]}})"), kTail + ".select",
     "selects no vertex of the parent 'body'"},
    {"EmptyIndices", with_tail(R"({"indices": []})"), kTail + ".select", "selects no vertex"},
    {"EmptyHalfSpace", with_tail(R"({"half_space": {"point": [0.6, 0, 0], "normal": [1, 0, 0]}})"),
     kTail + ".select", "half-space point (0.6, 0, 0)"},
    {"ZeroNormal", with_tail(R"({"half_space": {"point": [0, 0, 0], "normal": [0, 0, 0]}})"),
     kTail + ".select.half_space.normal", "non-zero direction"},
    {"UnknownGroupNoGroups", with_tail(R"({"group": "fin"})"), kTail + ".select.group",
     "'fin' is not a face group of the mesh (the mesh has no groups"},
    {"ChildFrameZeroX", tail_frame(R"({"origin": [0, 0, 0], "x": [0, 0, 0], "y": [0, 1, 0]})"),
     kTail + ".frame.x", "= (0, 0, 0) must be a finite, non-zero direction"},
    {"ChildFrameXParallelToY",
     tail_frame(R"({"origin": [0, 0, 0], "x": [0, 2, 0], "y": [0, -1, 0]})"), kTail + ".frame.y",
     "= (0, -1, 0) is zero or parallel to x = (0, 2, 0)"},
    {"ChildFrameZeroY", tail_frame(R"({"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 0, 0]})"),
     kTail + ".frame.y", "zero or parallel"},
    {"ChildFrameNoExtent",
     with_tail(R"({"indices": [5]})", "[]",
               R"(, "frame": {"origin": [0, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0]})"),
     kTail + ".frame.length", "no extent along x"},
    {"AutoFrameOfOneVertex", with_tail(R"({"indices": [0]})"), kTail + ".frame",
     "centroid coincides with its attachment"},
    {"RootFrameZeroX", rig_text(kBody, R"({"origin": [0, 0, 0], "x": [0, 0, 0], "y": [0, 1, 0]})"),
     "frame.x", "(frame of the root component 'body')"},
    {"RootFrameParallel",
     rig_text(kBody, R"({"origin": [0, 0, 0], "x": [1, 1, 0], "y": [2, 2, 0]})"), "frame.y",
     "parallel to x = (1, 1, 0)"},
};

INSTANTIATE_TEST_SUITE_P(Cases, ResolveRigInvalid, ::testing::ValuesIn(kResolveCases),
                         [](const ::testing::TestParamInfo<ResolveCase>& test_case) {
                           return test_case.param.name;
                         });

// Errors parse_rig_json cannot produce, from specs built in code.
TEST(ResolveRigErrors, ProgrammaticSpecsAreCheckedToo) {
  const RigSpec valid = parse_rig_json(with_tail(
      box_below(-0.3), R"([{"deformer": "hinge", "param": "a"}])",
      R"(, "frame": {"origin": [0, 0, 0], "x": [-1, 0, 0], "y": [0, 1, 0], "length": 0.2})"));
  ASSERT_NO_THROW(resolve_rig(valid, fish()));

  RigSpec spec = valid;
  spec.components[1].frame->length = 0.0;
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    kTail + ".frame.length", "= 0 must be finite and > 0"));
  spec = valid;
  spec.frame.mode = Mode::kExplicit;
  spec.frame.length = -1.0;
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument, "frame.length",
                    "root component 'body'"));
  spec = valid;
  spec.components[1].frame->origin.x = std::nan("");
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    kTail + ".frame.origin", "not finite"));
  spec = valid;
  spec.components[1].chain[0].options[0] = -0.5;  // the hinge's width
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    kTail + ".chain[0].width", "= -0.5 is not a valid hinge width"));
  spec = valid;
  spec.components[1].chain[0].param.clear();
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    kTail + ".chain[0].param", "is empty"));
  spec = valid;
  spec.components[1].name.clear();
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    "components[1].name", "is empty"));
  spec = valid;
  spec.components[0].frame = FrameSpec{};
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, fish()); }, ErrorCode::kInvalidArgument,
                    "components[0] 'body'.frame", "root component takes no frame"));

  // The mesh: invalid, and a group beyond its triangles.
  Mesh broken = fish();
  broken.positions[3].y = std::nanf("");
  EXPECT_THROW(resolve_rig(valid, broken), Error);
  Mesh grouped = fish();
  grouped.groups = {{"fin", grouped.triangle_count() - 1, 2}};
  spec = valid;
  spec.components[1].select = SelectorSpec{};
  spec.components[1].select.kind = Kind::kGroup;
  spec.components[1].select.group = "fin";
  EXPECT_TRUE(Fails([&] { resolve_rig(spec, grouped); }, ErrorCode::kInvalidMesh, "groups[0]",
                    "exceeds the mesh's"));
}

TEST(ResolveRigErrors, AutomaticRootFrameFailureSaysSo) {
  // The fish squashed onto its spine has no area: find_body_frame's error, code and
  // field, with the frame and the root named.
  Mesh line = fish();
  for (glm::vec3& p : line.positions) p = glm::vec3(p.x, 0.0f, 0.0f);
  EXPECT_TRUE(Fails([&] { resolve(rig_text(kBody, R"({"mode": "auto"})"), line); },
                    ErrorCode::kInvalidMesh, "mesh",
                    "frame: the automatic body frame (frame of the root component 'body') "
                    "failed: mesh has zero surface area"));
  EXPECT_TRUE(Fails([&] { resolve(R"({"components": [)" + kBody + "]}", line); },
                    ErrorCode::kInvalidMesh, "mesh", "automatic body frame"));
}

// ---------------------------------------------------------------------------------
// Parameter limits (RigParameter::limit)

// The largest |x| in `frame` of the vertices of component k and its descendants.
double subtree_x_max(const Rig& rig, const Mesh& mesh, std::size_t k, const BodyFrame& frame) {
  double x_max = 0.0;
  for (const std::uint32_t v : subtree_vertices(rig, k))
    x_max = std::max(x_max, std::abs(frame.point_to_local(glm::dvec3(mesh.positions[v])).x));
  return x_max;
}

constexpr double kPi = 3.14159265358979323846;

TEST(RigLimits, AParameterReadByTwoBendsTakesTheTighterLimit) {
  // body_m is read by the body's bend (x in [-0.5, 0.5]: 0.5 / 0.5 = 1) and by the
  // head's (its own frame from its seam at x = 0.3: a tighter limit); the hinges' angles
  // are limited to pi.
  const Rig rig = resolve(body_tail_fin_head());
  const std::size_t body = index_of(rig, "body"), head = index_of(rig, "head");
  const double body_limit = 0.5 / subtree_x_max(rig, fish(), body, rig.components[body].frame);
  const double head_limit = 0.5 / subtree_x_max(rig, fish(), head, rig.components[head].frame);
  EXPECT_NEAR(body_limit, 1.0, 1e-6);
  ASSERT_LT(head_limit, body_limit);
  const RigParameter& body_m = rig.parameters[rig.param_index("body_m")];
  EXPECT_DOUBLE_EQ(body_m.limit, head_limit);
  EXPECT_NE(body_m.limit_source.find("bend of 'head'"), std::string::npos) << body_m.limit_source;
  for (const char* angle : {"tail_angle", "head_angle", "fin_angle"}) {
    const RigParameter& parameter = rig.parameters[rig.param_index(angle)];
    EXPECT_DOUBLE_EQ(parameter.limit, kPi) << angle;
    EXPECT_NE(parameter.limit_source.find("hinge"), std::string::npos) << parameter.limit_source;
  }
  // The same bends reading two parameters: each takes its own stage's limit.
  std::string text = body_tail_fin_head();
  const std::size_t second = text.rfind("\"body_m\"");
  ASSERT_NE(second, std::string::npos);
  text.replace(second, 8, "\"head_m\"");
  const Rig split = resolve(text);
  EXPECT_DOUBLE_EQ(split.parameters[split.param_index("body_m")].limit, body_limit);
  EXPECT_DOUBLE_EQ(split.parameters[split.param_index("head_m")].limit, head_limit);
}

TEST(RigLimits, ShippedLowResolutionBlubRig) {
  // The body's exact bend reaches every vertex: 0.5 / the largest |x| in the automatic
  // body frame (0.8547, as `finflex rig-info` prints); the three fins' hinges: pi.
  const Rig rig =
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), blub());
  const BodyFrame& root = rig.components[0].frame;
  double x_max = 0.0;
  for (const glm::vec3& p : blub().positions)
    x_max = std::max(x_max, std::abs(root.point_to_local(glm::dvec3(p)).x));
  EXPECT_DOUBLE_EQ(rig.parameters[rig.param_index("body_m")].limit, 0.5 / x_max);
  EXPECT_NEAR(0.5 / x_max, 0.8547, 5e-5);
  for (const char* angle : {"tail_angle", "right_pectoral_angle", "left_pectoral_angle"})
    EXPECT_DOUBLE_EQ(rig.parameters[rig.param_index(angle)].limit, kPi) << angle;
}

// ---------------------------------------------------------------------------------
// The shipped rigs: what docs/rigs.md says of them

struct ShippedRig {
  const char* mesh;
  const char* rig;
  std::vector<std::size_t> own_vertices;  // body, caudal_fin, right_pectoral_fin, left_...
  double body_m_limit;                    // as rig-info prints it, 3 decimals
  // Per hinge parameter and sign: the angle (2 decimals) from which the ramp folds over
  // (count_folded_vertices > 0 at +0.01, none at -0.01); 0: none within pi.
  std::vector<std::pair<const char*, std::pair<double, double>>> fold_from;
};

TEST(ShippedRigs, ComponentsLimitsAndFoldOverAsDocumented) {
  const ShippedRig shipped[] = {
      {"blub/fish.obj",
       "rigs/blub.rig.json",
       {8650, 1566, 271, 299},
       0.894,
       {{"tail_angle", {2.39, 2.83}},
        {"right_pectoral_angle", {1.04, 1.50}},
        {"left_pectoral_angle", {1.37, 1.79}}}},
      {"blub/fish_low_resolution.obj",
       "rigs/blub_low_resolution.rig.json",
       {690, 105, 72, 78},
       0.855,
       {{"tail_angle", {2.60, 2.68}},
        {"right_pectoral_angle", {2.60, 0.0}},
        {"left_pectoral_angle", {2.61, 2.95}}}},
      {"barramundi/BarramundiFish.gltf",
       "rigs/barramundi.rig.json",
       {1640, 190, 179, 179},
       0.972,
       {{"tail_angle", {2.91, 0.0}},
        {"right_pectoral_angle", {0.0, 0.0}},
        {"left_pectoral_angle", {0.0, 0.0}}}},
  };
  for (const ShippedRig& c : shipped) {
    SCOPED_TRACE(c.rig);
    const Mesh mesh = load_mesh(test::data_path(c.mesh));
    const RiggedMesh model(mesh, resolve_rig(load_rig_file(test::data_path(c.rig)), mesh));
    const Rig& rig = model.rig();
    const std::vector<std::string> names = {"body", "caudal_fin", "right_pectoral_fin",
                                            "left_pectoral_fin"};
    ASSERT_EQ(rig.components.size(), names.size());
    for (std::size_t k = 0; k < names.size(); ++k) {
      EXPECT_EQ(rig.components[k].name, names[k]);
      EXPECT_EQ(rig.components[k].vertices.size(), c.own_vertices[k]) << names[k];
    }
    EXPECT_NEAR(rig.parameters[rig.param_index("body_m")].limit, c.body_m_limit, 5e-4);
    for (const auto& fold : c.fold_from) {
      const char* name = fold.first;
      const auto& from = fold.second;
      for (double sign : {1.0, -1.0}) {
        const double angle = sign > 0 ? from.first : from.second;
        auto folded = [&](double a) {
          RigParameters values(model, 1);
          values.set(0, name, static_cast<float>(sign * std::min(a, kPi)));
          return count_folded_vertices(model, values.view(), 0);
        };
        SCOPED_TRACE(std::string(name) + (sign > 0 ? " +" : " -"));
        if (angle == 0.0) {
          EXPECT_EQ(folded(kPi), 0u);
        } else {
          EXPECT_EQ(folded(angle - 0.01), 0u);
          EXPECT_GT(folded(angle + 0.01), 0u);
        }
      }
    }
  }
  // Blub's automatic body frame: s_x 2.905 mesh units.
  EXPECT_NEAR(find_body_frame(load_mesh(test::data_path("blub/fish.obj"))).length, 2.905, 5e-4);
}

// ---------------------------------------------------------------------------------
// single_bend_rig

TEST(SingleBendRig, OneBodyWithOneBendReadingM) {
  BodyFrame frame;
  frame.length = 2.0;
  const Rig rig = single_bend_rig(fish(), frame, BendMode::kPaper);
  ASSERT_EQ(rig.components.size(), 1u);
  expect_consistent(rig, fish());
  const RigComponent& body = rig.components[0];
  EXPECT_EQ(body.name, "body");
  EXPECT_EQ(body.parent, -1);
  EXPECT_EQ(body.vertices.size(), fish().vertex_count());
  EXPECT_EQ(body.frame.length, 2.0);
  ASSERT_EQ(body.chain.size(), 1u);
  EXPECT_EQ(body.chain[0].deformer, find_deformer_type("bend"));
  EXPECT_EQ(body.chain[0].options[0], 0.0);  // mode paper
  EXPECT_EQ(body.chain[0].param, 0u);
  EXPECT_NEAR(body.chain[0].geometry.x_max, 0.25, 1e-7);
  EXPECT_EQ(parameter_names(rig), std::vector<std::string>{"m"});
  EXPECT_DOUBLE_EQ(rig.parameters[0].limit, max_abs_m(0.25));
  EXPECT_EQ(rig.subtree_end, std::vector<std::size_t>{1});
  EXPECT_EQ(rig.depth(0), 0u);
  EXPECT_EQ(rig.param_index("m"), 0u);

  frame.length = 0.0;
  EXPECT_TRUE(Fails([&] { single_bend_rig(fish(), frame, BendMode::kExact); },
                    ErrorCode::kInvalidArgument, "frame.length", "must be finite and > 0"));
}

}  // namespace
}  // namespace finflex

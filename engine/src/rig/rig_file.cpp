// Rig files: JSON -> RigSpec (the schema is in finflex/rig.hpp).
//
// Strict on purpose: every key must be known, every value of the documented type, no
// key may appear twice in an object, so that a typo in a rig file is an error naming
// where it is instead of a silently ignored setting. Checks that need the mesh or the
// whole component tree (names, parents, vertices, frame geometry) are resolve_rig's.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/regular_file.hpp"
#include "finflex/deformer_type.hpp"
#include "finflex/error.hpp"
#include "finflex/rig.hpp"
#include "rig/json_document.hpp"

namespace finflex {
namespace {

using nlohmann::json;

// Values quoted in messages are cut to this many characters.
constexpr std::size_t kMaxShownChars = 80;

// ---------------------------------------------------------------------------------
// Fields and errors. A field is a path such as "components[1] 'tail'.select.box.min";
// messages start with it and name the value found and what was expected.

std::string member(const std::string& path, const std::string& key) {
  return detail::json_member(path, key);
}

std::string element(const std::string& path, std::size_t index) {
  return detail::json_element(path, index);
}

// The first `size` bytes of `text`, moved back to a UTF-8 character boundary.
std::string utf8_prefix(const std::string& text, std::size_t size) {
  if (size >= text.size()) return text;
  while (size > 0 && (static_cast<unsigned char>(text[size]) & 0xC0u) == 0x80u) --size;
  return text.substr(0, size);
}

std::string dump_scalar(const json& value) {
  if (value.is_string()) {  // only the start of a long string is shown
    const json start = utf8_prefix(value.get_ref<const std::string&>(), kMaxShownChars);
    return start.dump(-1, ' ', false, json::error_handler_t::replace);
  }
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

// The compact JSON text of `value` as json::dump() writes it, stopped once longer than
// `limit`: a loop over an explicit stack, so neither the depth of the value nor its
// size matters (dump() recurses, and would write all of it).
std::string limited_dump(const json& value, std::size_t limit) {
  struct Open {
    const json* container;
    json::const_iterator next;
    bool first;
  };
  std::vector<Open> stack;
  std::string out;
  const json* current = &value;
  for (;;) {
    if (current->is_object() || current->is_array()) {
      out += current->is_object() ? '{' : '[';
      stack.push_back({current, current->cbegin(), true});
    } else {
      out += dump_scalar(*current);
    }
    for (;;) {
      if (out.size() > limit || stack.empty()) return out;
      Open& top = stack.back();
      if (top.next == top.container->cend()) {
        out += top.container->is_object() ? '}' : ']';
        stack.pop_back();
        continue;
      }
      if (!top.first) out += ',';
      top.first = false;
      if (top.container->is_object()) out += dump_scalar(json(top.next.key())) + ':';
      current = &*top.next;
      ++top.next;
      break;
    }
  }
}

// The JSON text of `value`, shortened to kMaxShownChars.
std::string shown(const json& value) {
  std::string text = limited_dump(value, kMaxShownChars);
  if (text.size() > kMaxShownChars) text = utf8_prefix(text, kMaxShownChars - 3) + "...";
  return text;
}

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

// "<field> = <value>: expected <expected>".
[[noreturn]] void fail_value(const std::string& field, const json& value,
                             const std::string& expected) {
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " = " + shown(value) + ": expected " + expected);
}

std::string joined(std::initializer_list<const char*> names) {
  std::string list;
  for (const char* name : names) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

// Throws for the first key of `object` not in `allowed`.
void check_keys(const json& object, const std::string& path,
                std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    bool known = false;
    for (const char* name : allowed) known = known || item.key() == name;
    if (!known) {
      fail(member(path, item.key()),
           "unknown key '" + item.key() + "' (expected one of: " + joined(allowed) + ")");
    }
  }
}

const json& required(const json& object, const std::string& path, const char* key,
                     const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) fail(member(path, key), "missing (" + what + ")");
  return *it;
}

void expect_object(const json& value, const std::string& field, const std::string& expected) {
  if (!value.is_object()) fail_value(field, value, expected);
}

// ---------------------------------------------------------------------------------
// Scalars and vectors

std::string parse_name(const json& value, const std::string& field, const std::string& what) {
  if (!value.is_string() || value.get_ref<const std::string&>().empty()) {
    fail_value(field, value, "a non-empty string (" + what + ")");
  }
  return value.get<std::string>();
}

double parse_number(const json& value, const std::string& field, const std::string& expected) {
  if (!value.is_number()) fail_value(field, value, expected);
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail_value(field, value, expected);
  return number;
}

double parse_positive(const json& value, const std::string& field) {
  const double number = parse_number(value, field, "a finite number > 0");
  if (!(number > 0.0)) fail_value(field, value, "a finite number > 0");
  return number;
}

glm::dvec3 parse_vec3(const json& value, const std::string& field) {
  const char* const expected = "an array of 3 finite numbers";
  if (!value.is_array() || value.size() != 3) fail_value(field, value, expected);
  glm::dvec3 v{0.0};
  for (glm::length_t i = 0; i < 3; ++i) {
    const json& component = value[static_cast<std::size_t>(i)];
    if (!component.is_number()) fail_value(field, value, expected);
    v[i] = component.get<double>();
    if (!std::isfinite(v[i])) fail_value(field, value, expected);
  }
  return v;
}

// ---------------------------------------------------------------------------------
// Frames

// {"mode": "auto"} | {"mode": "identity"} | {["mode": "explicit",] "origin", "x", "y"
// [, "length"]}.
FrameSpec parse_frame(const json& value, const std::string& field) {
  expect_object(value, field,
                "an object: {\"mode\": \"auto\"}, {\"mode\": \"identity\"} or "
                "{\"origin\": [x, y, z], \"x\": [..], \"y\": [..], \"length\": s}");
  FrameSpec frame;
  frame.mode = FrameSpec::Mode::kExplicit;
  if (const auto it = value.find("mode"); it != value.end()) {
    const std::string mode_field = member(field, "mode");
    const char* const modes = "\"auto\", \"identity\" or \"explicit\"";
    if (!it->is_string()) fail_value(mode_field, *it, modes);
    const std::string& mode = it->get_ref<const std::string&>();
    if (mode == "auto" || mode == "identity") {
      frame.mode = mode == "auto" ? FrameSpec::Mode::kAuto : FrameSpec::Mode::kIdentity;
      for (const auto& item : value.items()) {
        if (item.key() != "mode") {
          fail(member(field, item.key()), "unexpected with mode '" + mode +
                                              "' (origin, x, y and length belong to an explicit "
                                              "frame: drop the mode or this key)");
        }
      }
      return frame;
    }
    if (mode != "explicit") fail_value(mode_field, *it, modes);
  }
  check_keys(value, field, {"mode", "origin", "x", "y", "length"});
  const char* const what = "an explicit frame needs origin, x and y";
  frame.origin = parse_vec3(required(value, field, "origin", what), member(field, "origin"));
  frame.x = parse_vec3(required(value, field, "x", what), member(field, "x"));
  frame.y = parse_vec3(required(value, field, "y", what), member(field, "y"));
  if (const auto it = value.find("length"); it != value.end()) {
    frame.length = parse_positive(*it, member(field, "length"));
  }
  return frame;
}

// ---------------------------------------------------------------------------------
// Selectors

std::vector<std::uint32_t> parse_indices(const json& value, const std::string& field) {
  if (!value.is_array()) fail_value(field, value, "an array of vertex indices");
  std::vector<std::uint32_t> indices;
  indices.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    const json& index = value[i];
    if (!index.is_number_unsigned() ||
        index.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
      fail_value(element(field, i), index, "a vertex index (an integer in [0, 2^32))");
    }
    indices.push_back(static_cast<std::uint32_t>(index.get<std::uint64_t>()));
  }
  return indices;
}

// "all" | {"indices": [..]} | {"group": "name"} | {"box": {"min", "max"}} |
// {"half_space": {"point", "normal"}}.
SelectorSpec parse_selector(const json& value, const std::string& field) {
  const char* const expected =
      "\"all\" or an object with one key: indices, group, box or half_space";
  SelectorSpec select;
  if (value.is_string()) {
    if (value.get_ref<const std::string&>() != "all") fail_value(field, value, expected);
    select.kind = SelectorSpec::Kind::kAll;
    return select;
  }
  if (!value.is_object() || value.empty()) fail_value(field, value, expected);
  check_keys(value, field, {"indices", "group", "box", "half_space"});
  if (value.size() != 1) fail_value(field, value, expected + std::string(" (not several)"));
  const std::string key = value.begin().key();
  const json& body = value.begin().value();
  const std::string body_field = member(field, key);
  if (key == "indices") {
    select.kind = SelectorSpec::Kind::kIndices;
    select.indices = parse_indices(body, body_field);
  } else if (key == "group") {
    select.kind = SelectorSpec::Kind::kGroup;
    select.group = parse_name(body, body_field, "a face group of the mesh");
  } else if (key == "box") {
    select.kind = SelectorSpec::Kind::kBox;
    expect_object(body, body_field, "an object {\"min\": [x, y, z], \"max\": [x, y, z]}");
    check_keys(body, body_field, {"min", "max"});
    const char* const what = "a box needs min and max";
    select.box_min = parse_vec3(required(body, body_field, "min", what), member(body_field, "min"));
    select.box_max = parse_vec3(required(body, body_field, "max", what), member(body_field, "max"));
    for (glm::length_t i = 0; i < 3; ++i) {
      if (select.box_max[i] < select.box_min[i]) {
        fail_value(member(body_field, "max"), body["max"],
                   "max >= min = " + shown(body["min"]) + " in every coordinate");
      }
    }
  } else {
    select.kind = SelectorSpec::Kind::kHalfSpace;
    expect_object(body, body_field, "an object {\"point\": [x, y, z], \"normal\": [x, y, z]}");
    check_keys(body, body_field, {"point", "normal"});
    const char* const what = "a half-space needs point and normal";
    select.point =
        parse_vec3(required(body, body_field, "point", what), member(body_field, "point"));
    select.normal =
        parse_vec3(required(body, body_field, "normal", what), member(body_field, "normal"));
  }
  return select;
}

// ---------------------------------------------------------------------------------
// Stages and components

// {"deformer": <name>, "param": p, <the deformer's options>}: the deformers and their
// options are the registry's (finflex/deformer_type.hpp).

// What a number option takes, for messages: "a finite number >= 0 (the ramp's width)".
std::string expected_number(const DeformerOption& option) {
  std::ostringstream text;
  text.precision(9);
  text << (option.integer ? "a whole number" : "a finite number");
  if (std::isinf(option.maximum)) {
    text << " >= " << option.minimum;
  } else {
    text << " in [" << option.minimum << ", " << option.maximum << "]";
  }
  text << " (" << option.meaning << ")";
  return text.str();
}

std::string expected_choice(const DeformerOption& option) {
  std::string list;
  for (std::size_t k = 0; k < option.choices.size(); ++k) {
    if (k > 0) list += k + 1 == option.choices.size() ? " or " : ", ";
    list += "\"" + std::string(option.choices[k]) + "\"";
  }
  return list;
}

double parse_option(const json& value, const std::string& field, const DeformerOption& option) {
  if (!option.choices.empty()) {
    for (std::size_t k = 0; k < option.choices.size(); ++k) {
      if (value.is_string() && value.get_ref<const std::string&>() == option.choices[k]) {
        return static_cast<double>(k);
      }
    }
    fail_value(field, value, expected_choice(option));
  }
  const double number = parse_number(value, field, expected_number(option));
  if (number < option.minimum || number > option.maximum ||
      (option.integer && number != std::floor(number))) {
    fail_value(field, value, expected_number(option));
  }
  return number;
}

// The registered deformers that have an option `key`, e.g. "the bend".
std::string owners_of(const std::string& key) {
  std::string owners;
  for (const DeformerType* type : deformer_types()) {
    for (const DeformerOption& option : type->options) {
      if (key == option.key)
        owners += (owners.empty() ? "the " : " and the ") + std::string(type->name);
    }
  }
  return owners;
}

StageSpec parse_stage(const json& value, const std::string& field) {
  expect_object(value, field,
                "an object {\"deformer\": " + deformer_type_names() + ", \"param\": ...}");
  const std::string deformer_field = member(field, "deformer");
  const json& deformer = required(value, field, "deformer", deformer_type_names());
  const DeformerType* type =
      deformer.is_string() ? find_deformer_type(deformer.get<std::string>()) : nullptr;
  if (type == nullptr) fail_value(deformer_field, deformer, deformer_type_names());
  StageSpec stage;
  stage.deformer = type;
  stage.options = default_options(*type);
  for (const auto& item : value.items()) {
    const std::string& key = item.key();
    if (key == "deformer" || key == "param") continue;
    const auto option = std::find_if(type->options.begin(), type->options.end(),
                                     [&](const DeformerOption& o) { return key == o.key; });
    if (option == type->options.end()) {
      const std::string owners = owners_of(key);
      if (!owners.empty()) {
        fail(member(field, key),
             "applies to " + owners + " only (this stage is a " + type->name + ")");
      }
      std::string keys = "deformer, param";
      for (const DeformerOption& o : type->options) keys += ", " + std::string(o.key);
      fail(member(field, key),
           "unknown key '" + key + "' (a " + type->name + " stage takes: " + keys + ")");
    }
    stage.options[static_cast<std::size_t>(option - type->options.begin())] =
        parse_option(item.value(), member(field, key), *option);
  }
  stage.param = parse_name(required(value, field, "param", "the parameter this stage reads"),
                           member(field, "param"), "the parameter this stage reads");
  return stage;
}

ComponentSpec parse_component(const json& value, std::size_t index) {
  const std::string at = element("components", index);
  expect_object(value, at, "an object {\"name\", [\"parent\",] \"select\", \"chain\"}");
  ComponentSpec component;
  component.name = parse_name(required(value, at, "name", "every component needs a name"),
                              member(at, "name"), "the component's name");
  const std::string field = at + " '" + component.name + "'";
  check_keys(value, field, {"name", "parent", "select", "frame", "chain"});
  if (const auto it = value.find("parent"); it != value.end()) {
    component.parent =
        parse_name(*it, member(field, "parent"), "a component's name; omit the key for the root");
  }
  component.select = parse_selector(
      required(value, field, "select", "\"all\" for the root, else which vertices of the parent"),
      member(field, "select"));
  if (const auto it = value.find("frame"); it != value.end()) {
    if (component.parent.empty()) {
      fail(member(field, "frame"),
           "the root component takes no frame: its frame is the rig's top-level \"frame\"");
    }
    component.frame = parse_frame(*it, member(field, "frame"));
  }
  const std::string chain_field = member(field, "chain");
  const json& chain = required(value, field, "chain", "the component's deformers; [] for none");
  if (!chain.is_array()) fail_value(chain_field, chain, "an array of deformer stages");
  for (std::size_t i = 0; i < chain.size(); ++i) {
    component.chain.push_back(parse_stage(chain[i], element(chain_field, i)));
  }
  return component;
}

// ---------------------------------------------------------------------------------
// The document

}  // namespace

RigSpec parse_rig_json(const std::string& text) {
  const json document = detail::parse_rig_document(text);
  expect_object(document, "rig", "an object {[\"frame\": ...,] \"components\": [...]}");
  check_keys(document, "", {"frame", "components"});
  RigSpec spec;
  if (const auto it = document.find("frame"); it != document.end()) {
    spec.frame = parse_frame(*it, "frame");
  }
  const json& components =
      required(document, "", "components", "the rig's components, the root first or not");
  if (!components.is_array()) {
    fail_value("components", components, "an array of components");
  }
  for (std::size_t i = 0; i < components.size(); ++i) {
    spec.components.push_back(parse_component(components[i], i));
  }
  return spec;
}

RigSpec load_rig_file(const std::string& path) {
  const std::string text = detail::read_regular_file(path, "path", "a rig file");
  try {
    return parse_rig_json(text);
  } catch (const Error& e) {
    throw Error(e.code(), e.field(), "'" + path + "': " + e.what());
  }
}

}  // namespace finflex

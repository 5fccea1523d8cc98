// The component tree of a rig file (spec indices), built and checked without
// recursion: parent links by name, one root, no cycle, the depth and path limits of
// finflex/rig.hpp. Shared by resolve_rig's steps; the messages name the component.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "finflex/rig.hpp"

namespace finflex::detail {

constexpr std::size_t kNoComponent = std::numeric_limits<std::size_t>::max();

struct RigTree {
  std::size_t root = kNoComponent;
  std::vector<std::size_t> parent;                 // kNoComponent for the root
  std::vector<std::vector<std::size_t>> children;  // in spec order
  std::vector<std::size_t> order;                  // depth-first, children in spec order
  std::vector<std::size_t> depth;                  // the root is 0
};

// Throws kInvalidArgument: "<field>: <message>", or "<field> = <value> ..." when the
// message starts with "= ".
[[noreturn]] void fail_rig(const std::string& field, const std::string& message);

// "components[i] 'name'".
std::string component_field(const RigSpec& spec, std::size_t i);

// Up to `shown` of `names` joined by ", " (each wrapped in `quote`), then "... (N in
// all)": messages stay short whatever the rig's size.
std::string short_list(const std::vector<std::string>& names, const char* quote = "",
                       std::size_t shown = 20);

// Checks names (non-empty, unique), parents (known, one root, no cycle), the root's
// selector and frame, the nesting depth (<= kMaxRigDepth) and the stages on every path
// (<= kMaxRigPathStages); work in O(components + stages) (times log for the names).
RigTree build_rig_tree(const RigSpec& spec);

}  // namespace finflex::detail

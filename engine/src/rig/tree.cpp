// The component tree of a rig file (rig/tree.hpp): loops and explicit stacks only, so
// a rig nested thousands of levels deep is refused with a message, never a crash.
#include "rig/tree.hpp"

#include <algorithm>
#include <map>

#include "finflex/error.hpp"

namespace finflex::detail {
namespace {

std::string list_of_names(const RigSpec& spec) {
  std::vector<std::string> names;
  names.reserve(spec.components.size());
  for (const ComponentSpec& c : spec.components) names.push_back(c.name);
  return short_list(names);
}

void check_names(const RigSpec& spec) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < spec.components.size(); ++i) {
    const std::string& name = spec.components[i].name;
    const std::string at = "components[" + std::to_string(i) + "]";
    if (name.empty()) fail_rig(at + ".name", "is empty: every component needs a name");
    const auto [it, inserted] = seen.emplace(name, i);
    if (!inserted) {
      fail_rig(component_field(spec, i) + ".name",
               "'" + name + "' is also the name of components[" + std::to_string(it->second) +
                   "]: names must be unique");
    }
  }
}

// Parent links by name; exactly one root. Names are unique (check_names).
RigTree link_parents(const RigSpec& spec) {
  const std::size_t n = spec.components.size();
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < n; ++i) index.emplace(spec.components[i].name, i);
  RigTree tree;
  tree.parent.assign(n, kNoComponent);
  tree.children.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& parent = spec.components[i].parent;
    if (parent.empty()) continue;
    const auto it = index.find(parent);
    if (it == index.end()) {
      fail_rig(component_field(spec, i) + ".parent", "'" + parent +
                                                         "' is not a component of the rig (its "
                                                         "components: " +
                                                         list_of_names(spec) + ")");
    }
    tree.parent[i] = it->second;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (tree.parent[i] != kNoComponent) continue;
    if (tree.root != kNoComponent) {
      fail_rig(component_field(spec, i) + ".parent",
               "missing, and '" + spec.components[tree.root].name + "' (components[" +
                   std::to_string(tree.root) +
                   "]) has no parent either: a rig has exactly one root, every other component "
                   "names its parent");
    }
    tree.root = i;
  }
  if (tree.root == kNoComponent) {
    fail_rig("components", "no root component: every component names a parent (" +
                               list_of_names(spec) + "); the root (the whole body) has none");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (tree.parent[i] != kNoComponent) tree.children[tree.parent[i]].push_back(i);
  }
  return tree;
}

// Depth-first order from the root (children in spec order) with each component's
// depth; components the walk does not reach are left out.
void walk(RigTree& tree) {
  const std::size_t n = tree.parent.size();
  tree.order.clear();
  tree.order.reserve(n);
  tree.depth.assign(n, 0);
  std::vector<std::size_t> stack = {tree.root};
  while (!stack.empty()) {
    const std::size_t c = stack.back();
    stack.pop_back();
    tree.order.push_back(c);
    if (tree.parent[c] != kNoComponent) tree.depth[c] = tree.depth[tree.parent[c]] + 1;
    for (auto it = tree.children[c].rbegin(); it != tree.children[c].rend(); ++it) {
      stack.push_back(*it);
    }
  }
}

// Throws for a component whose parent chain loops (never reaches the root), naming
// the loop. With one root and every parent known, those are the ones walk() missed.
void check_cycles(const RigSpec& spec, const RigTree& tree) {
  const std::size_t n = spec.components.size();
  if (tree.order.size() == n) return;
  std::vector<bool> reached(n, false);
  for (const std::size_t c : tree.order) reached[c] = true;
  const std::size_t i =
      static_cast<std::size_t>(std::find(reached.begin(), reached.end(), false) - reached.begin());
  std::size_t first = i;  // n steps up from i surely land on the loop
  for (std::size_t k = 0; k < n; ++k) first = tree.parent[first];
  for (std::size_t c = tree.parent[first], start = first; c != start; c = tree.parent[c]) {
    first = std::min(first, c);  // the loop's first component in the spec
  }
  std::vector<std::string> loop = {spec.components[first].name};
  for (std::size_t c = tree.parent[first]; c != first; c = tree.parent[c]) {
    loop.push_back(spec.components[c].name);
  }
  loop.push_back(spec.components[first].name);
  std::string text;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    if (k > 0 && loop.size() > 12 && k == 10) {
      text += " -> ... (" + std::to_string(loop.size() - 1) + " components in the loop)";
      k = loop.size() - 1;
    }
    text += (k ? " -> '" : "'") + loop[k] + "'";
  }
  fail_rig(component_field(spec, first) + ".parent",
           "the parent chain loops (" + text + ", child -> parent) and never reaches the root '" +
               spec.components[tree.root].name + "'");
}

// The depth and path-length limits (finflex/rig.hpp), in depth-first order.
void check_limits(const RigSpec& spec, const RigTree& tree) {
  std::vector<std::size_t> path_stages(spec.components.size(), 0);
  for (const std::size_t c : tree.order) {
    const std::size_t parent = tree.parent[c];
    if (tree.depth[c] > kMaxRigDepth) {
      fail_rig(component_field(spec, c) + ".parent",
               "'" + spec.components[c].name + "' is nested " + std::to_string(tree.depth[c]) +
                   " levels below the root '" + spec.components[tree.root].name +
                   "': a rig nests at most " + std::to_string(kMaxRigDepth) +
                   " levels (kMaxRigDepth)");
    }
    path_stages[c] =
        spec.components[c].chain.size() + (parent == kNoComponent ? 0 : path_stages[parent]);
    if (path_stages[c] > kMaxRigPathStages) {
      fail_rig(component_field(spec, c) + ".chain",
               "the path of '" + spec.components[c].name +
                   "' (its chain, then its ancestors') has " + std::to_string(path_stages[c]) +
                   " stages: at most " + std::to_string(kMaxRigPathStages) +
                   " (kMaxRigPathStages)");
    }
  }
}

}  // namespace

void fail_rig(const std::string& field, const std::string& message) {
  const char* const separator = message.rfind("= ", 0) == 0 ? " " : ": ";
  throw Error(ErrorCode::kInvalidArgument, field, field + separator + message);
}

std::string component_field(const RigSpec& spec, std::size_t i) {
  return "components[" + std::to_string(i) + "] '" + spec.components[i].name + "'";
}

std::string short_list(const std::vector<std::string>& names, const char* quote,
                       std::size_t shown) {
  std::string list;
  for (std::size_t k = 0; k < names.size() && k < shown; ++k) {
    list += (k ? ", " : "") + std::string(quote) + names[k] + quote;
  }
  if (names.size() > shown) list += ", ... (" + std::to_string(names.size()) + " in all)";
  return list;
}

RigTree build_rig_tree(const RigSpec& spec) {
  if (spec.components.empty()) {
    fail_rig("components", "is empty: a rig needs at least its root component (select \"all\")");
  }
  check_names(spec);
  RigTree tree = link_parents(spec);
  walk(tree);
  check_cycles(spec, tree);
  const ComponentSpec& root = spec.components[tree.root];
  const std::string field = component_field(spec, tree.root);
  if (root.select.kind != SelectorSpec::Kind::kAll) {
    fail_rig(field + ".select",
             "the root component must select \"all\" (its children select parts)");
  }
  if (root.frame) {
    fail_rig(field + ".frame",
             "the root component takes no frame: its frame is the rig's top-level \"frame\"");
  }
  check_limits(spec, tree);
  return tree;
}

}  // namespace finflex::detail

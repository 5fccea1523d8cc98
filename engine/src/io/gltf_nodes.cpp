// The scene's node hierarchy: checked to be a forest, then ordered depth-first
// without recursion.
#include <cstdint>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "io/gltf.hpp"

namespace finflex::io {
namespace {

std::string node_field(std::size_t index) { return "nodes[" + std::to_string(index) + "]"; }

constexpr std::int64_t kNoParent = -1;

// Per node, the node that lists it as a child (kNoParent for none). Throws for a
// child that does not exist, a node listed twice by its parent, or one listed by two
// parents.
std::vector<std::int64_t> parents_of(const tinygltf::Model& model) {
  const std::size_t count = model.nodes.size();
  std::vector<std::int64_t> parent(count, kNoParent);
  for (std::size_t p = 0; p < count; ++p) {
    const std::vector<int>& children = model.nodes[p].children;
    for (std::size_t k = 0; k < children.size(); ++k) {
      const int child = children[k];
      if (child < 0 || static_cast<std::size_t>(child) >= count) {
        throw_gltf_format(node_field(p) + ".children[" + std::to_string(k) + "]",
                          "node " + std::to_string(child) + " does not exist (" +
                              std::to_string(count) + " nodes)");
      }
      const auto c = static_cast<std::size_t>(child);
      if (parent[c] == static_cast<std::int64_t>(p)) {
        throw_gltf_format(node_field(c), "is listed twice in " + node_field(p) +
                                             ".children (a node has one place in the scene)");
      }
      if (parent[c] != kNoParent) {
        throw_gltf_format(node_field(c),
                          "is a child of both " + node_field(static_cast<std::size_t>(parent[c])) +
                              " and " + node_field(p) + " (a node has at most one parent)");
      }
      parent[c] = static_cast<std::int64_t>(p);
    }
  }
  return parent;
}

// Throws if following the parents from some node comes back to it. O(nodes): each
// node is walked through once.
void check_no_cycle(const std::vector<std::int64_t>& parent) {
  enum : std::uint8_t { kNew, kOnWalk, kDone };
  std::vector<std::uint8_t> state(parent.size(), kNew);
  std::vector<std::size_t> walk;
  for (std::size_t start = 0; start < parent.size(); ++start) {
    walk.clear();
    std::int64_t n = static_cast<std::int64_t>(start);
    while (n != kNoParent && state[static_cast<std::size_t>(n)] == kNew) {
      state[static_cast<std::size_t>(n)] = kOnWalk;
      walk.push_back(static_cast<std::size_t>(n));
      n = parent[static_cast<std::size_t>(n)];
    }
    if (n != kNoParent && state[static_cast<std::size_t>(n)] == kOnWalk) {
      throw_gltf_format(node_field(static_cast<std::size_t>(n)),
                        "is its own ancestor (cycle in children)");
    }
    for (const std::size_t w : walk) state[w] = kDone;
  }
}

// The scene's root nodes: the default scene's, else scene 0's, else (no scenes)
// every node without a parent. Scene roots must exist, be listed once and have no
// parent.
std::vector<std::size_t> root_nodes(const tinygltf::Model& model,
                                    const std::vector<std::int64_t>& parent) {
  std::vector<std::size_t> roots;
  if (model.scenes.empty()) {
    for (std::size_t i = 0; i < parent.size(); ++i) {
      if (parent[i] == kNoParent) roots.push_back(i);
    }
    return roots;
  }
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (static_cast<std::size_t>(scene) >= model.scenes.size()) {
    throw_gltf_format("scene", std::to_string(scene) + " does not exist (" +
                                   std::to_string(model.scenes.size()) + " scenes)");
  }
  const std::string scene_field = "scenes[" + std::to_string(scene) + "].nodes";
  const std::vector<int>& listed = model.scenes[static_cast<std::size_t>(scene)].nodes;
  std::vector<bool> seen(model.nodes.size(), false);
  for (std::size_t k = 0; k < listed.size(); ++k) {
    const int node = listed[k];
    if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size()) {
      throw_gltf_format(scene_field + "[" + std::to_string(k) + "]",
                        "node " + std::to_string(node) + " does not exist (" +
                            std::to_string(model.nodes.size()) + " nodes)");
    }
    const auto n = static_cast<std::size_t>(node);
    if (seen[n]) throw_gltf_format(node_field(n), "is listed twice in " + scene_field);
    seen[n] = true;
    if (parent[n] != kNoParent) {
      throw_gltf_format(node_field(n), "is listed in " + scene_field + " but is a child of " +
                                           node_field(static_cast<std::size_t>(parent[n])) +
                                           " (scene nodes must be root nodes)");
    }
    roots.push_back(n);
  }
  return roots;
}

}  // namespace

std::vector<PlacedNode> scene_nodes(const tinygltf::Model& model) {
  const std::vector<std::int64_t> parent = parents_of(model);
  check_no_cycle(parent);
  const std::vector<std::size_t> roots = root_nodes(model, parent);

  struct Pending {
    std::size_t node;
    std::int64_t parent_slot;  // into `order`
    std::size_t depth;         // roots: 1
  };
  std::vector<Pending> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, 1});
  std::vector<PlacedNode> order;
  std::vector<bool> placed(model.nodes.size(), false);
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    if (pending.depth > kMaxNodeDepth) {
      throw_gltf_format(node_field(pending.node), "is nested " + std::to_string(pending.depth) +
                                                      " levels deep, more than the limit of " +
                                                      std::to_string(kMaxNodeDepth));
    }
    // The checks above make a second visit impossible; this keeps the walk linear
    // should they ever miss one.
    if (placed[pending.node]) throw_gltf_format(node_field(pending.node), "is reached twice");
    placed[pending.node] = true;
    const auto slot = static_cast<std::int64_t>(order.size());
    order.push_back({pending.node, pending.parent_slot});
    const std::vector<int>& children = model.nodes[pending.node].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      stack.push_back({static_cast<std::size_t>(*it), slot, pending.depth + 1});
    }
  }
  return order;
}

}  // namespace finflex::io

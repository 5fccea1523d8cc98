#include "rig/structure.hpp"

#include <string>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::detail {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw Error(ErrorCode::kInvalidArgument, "rig", "rig: " + where + ": " + problem);
}

std::string at(std::size_t k) { return "components[" + std::to_string(k) + "]"; }

void check_parameters(const Rig& rig) {
  const std::size_t row = rig.values_per_instance();
  for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
    const RigParameter& parameter = rig.parameters[p];
    if (parameter.offset > row || parameter.count > row - parameter.offset) {
      fail("parameters[" + std::to_string(p) + "] '" + parameter.name + "'",
           "values " + std::to_string(parameter.offset) + " + " + std::to_string(parameter.count) +
               " lie outside the instance's " + std::to_string(row) + " values");
    }
  }
}

void check_stages(const Rig& rig, std::size_t k) {
  const RigComponent& component = rig.components[k];
  for (std::size_t s = 0; s < component.chain.size(); ++s) {
    const RigStage& stage = component.chain[s];
    const std::string where = at(k) + " '" + component.name + "'.chain[" + std::to_string(s) + "]";
    if (stage.deformer == nullptr) fail(where, "has no deformer");
    if (stage.param >= rig.parameters.size()) {
      fail(where, "param = " + std::to_string(stage.param) + " is out of range (" +
                      std::to_string(rig.parameters.size()) + " parameters)");
    }
    const std::size_t takes = stage.deformer->value_count(stage.options);
    if (rig.parameters[stage.param].count != takes) {
      fail(where, "reads '" + rig.parameters[stage.param].name + "' (" +
                      std::to_string(rig.parameters[stage.param].count) + " values), a " +
                      stage.deformer->name + " stage takes " + std::to_string(takes));
    }
  }
}

}  // namespace

void check_rig_structure(const Rig& rig) {
  const std::size_t n = rig.components.size();
  if (rig.subtree_end.size() != n) {
    fail("subtree_end", std::to_string(rig.subtree_end.size()) + " entries for " +
                            std::to_string(n) + " components");
  }
  check_parameters(rig);
  std::vector<std::size_t> depth(n, 0), path_stages(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const int parent = rig.components[k].parent;
    if (k == 0 ? parent != -1 : (parent < 0 || static_cast<std::size_t>(parent) >= k)) {
      fail(at(k) + ".parent = " + std::to_string(parent),
           k == 0 ? "the root comes first, with parent -1"
                  : "a parent comes before its children (depth-first order), one root");
    }
    const std::size_t p = static_cast<std::size_t>(parent);
    depth[k] = k == 0 ? 0 : depth[p] + 1;
    path_stages[k] = rig.components[k].chain.size() + (k == 0 ? 0 : path_stages[p]);
    if (depth[k] > kMaxRigDepth) {
      fail(at(k) + " '" + rig.components[k].name + "'",
           "nested " + std::to_string(depth[k]) + " levels below the root: at most " +
               std::to_string(kMaxRigDepth) + " (kMaxRigDepth)");
    }
    if (path_stages[k] > kMaxRigPathStages) {
      fail(at(k) + " '" + rig.components[k].name + "'",
           "its path has " + std::to_string(path_stages[k]) + " stages: at most " +
               std::to_string(kMaxRigPathStages) + " (kMaxRigPathStages)");
    }
    check_stages(rig, k);
  }
  for (std::size_t k = n; k-- > 0;) {
    std::size_t end = k + 1;
    while (end < n && depth[end] > depth[k]) end = rig.subtree_end[end];
    if (rig.subtree_end[k] != end) {
      fail("subtree_end[" + std::to_string(k) + "] = " + std::to_string(rig.subtree_end[k]),
           "the subtree of '" + rig.components[k].name + "' ends at " + std::to_string(end));
    }
  }
}

}  // namespace finflex::detail

#include "cl/launch_plan.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace finflex::detail {

const char* stage_function(const RigStage& stage, bool from_rest) {
  if (from_rest && stage.deformer->cl_rest_function) return stage.deformer->cl_rest_function;
  return stage.deformer->cl_function(stage.options);
}

std::vector<const char*> path_functions(const RiggedMesh& model, std::size_t c) {
  std::vector<const char*> functions;
  for (const StageRef& ref : model.paths()[c])
    functions.push_back(stage_function(model.rig().stage(ref), functions.empty()));
  return functions;
}

std::size_t path_table_width(const RiggedMesh& model) {
  return std::max<std::size_t>(model.longest_path(), 1);
}

FrameLinks frame_links(const RiggedMesh& model) {
  const Rig& rig = model.rig();
  FrameLinks links;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;  // a pair's link
  links.of_path.resize(model.paths().size());
  for (std::size_t c = 0; c < model.paths().size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    for (std::size_t j = 0; j + 1 < path.size(); ++j) {
      const std::pair<std::size_t, std::size_t> link{
          stage_index(rig, path[j].component, path[j].stage),
          stage_index(rig, path[j + 1].component, path[j + 1].stage)};
      const auto [at, added] = index.emplace(link, links.pairs.size());
      if (added) links.pairs.push_back(link);
      links.of_path[c].push_back(at->second);
    }
  }
  return links;
}

std::vector<std::uint32_t> group_path_table(const RiggedMesh& model, const SlotLayout& slots,
                                            std::size_t group_size) {
  const Rig& rig = model.rig();
  const std::size_t groups = slots.slot_count / group_size;
  const std::size_t width = path_table_width(model);
  const FrameLinks links = frame_links(model);
  std::vector<std::uint32_t> table(2 * width * groups, 0u);
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    for (std::size_t g = slots.first_slot[c] / group_size; g < slots.first_slot[c + 1] / group_size;
         ++g) {
      for (std::size_t j = 0; j < path.size(); ++j) {
        table[j * groups + g] =
            static_cast<std::uint32_t>(stage_index(rig, path[j].component, path[j].stage));
        if (j + 1 < path.size()) {
          table[(width + j) * groups + g] = static_cast<std::uint32_t>(links.of_path[c][j]);
        }
      }
    }
  }
  return table;
}

PassPlan make_pass_plan(const RiggedMesh& model, const SlotLayout& slots, std::size_t group_size,
                        bool share_code) {
  const Rig& rig = model.rig();
  const std::size_t count = rig.components.size();
  const std::vector<std::vector<StageRef>>& paths = model.paths();
  std::vector<PlaneSet> location(count, PlaneSet::kRest);  // where component c's vertices are
  std::vector<std::size_t> applied(count, 0);              // stages applied to them so far
  auto groups_of = [&](std::size_t c) {
    return std::make_pair(slots.first_slot[c] / group_size, slots.first_slot[c + 1] / group_size);
  };

  PassPlan plan;
  double scratch_records = 0.0;
  auto add_step = [&](std::vector<PassStep>& steps, PassStep step) {
    const double slots_in_step = double((step.end_group - step.first_group) * group_size);
    if (step.source != PlaneSet::kRest) scratch_records += slots_in_step;
    if (step.target != PlaneSet::kOutput) scratch_records += slots_in_step;
    if (!steps.empty()) {
      PassStep& previous = steps.back();
      if (previous.end_group == step.first_group && previous.source == step.source &&
          previous.target == step.target && previous.function == step.function &&
          previous.path_position == step.path_position &&
          (share_code || previous.stage == step.stage)) {
        previous.end_group = step.end_group;  // contiguous and alike: one branch
        return;
      }
    }
    steps.push_back(step);
  };

  // The components at each depth (depths computed once, parents first): each pass
  // visits only the components it has a stage of, so planning takes O(stages x their
  // subtrees) <= O(components x kMaxRigPathStages).
  std::vector<std::vector<std::size_t>> at_depth;
  {
    std::vector<std::size_t> depth(count, 0);
    for (std::size_t c = 0; c < count; ++c) {
      const int parent = rig.components[c].parent;
      depth[c] = parent < 0 ? 0 : depth[static_cast<std::size_t>(parent)] + 1;
      if (at_depth.size() <= depth[c]) at_depth.resize(depth[c] + 1);
      at_depth[depth[c]].push_back(c);
    }
  }
  for (std::size_t depth = at_depth.size(); depth-- > 0;) {
    for (std::size_t position = 0;; ++position) {
      std::vector<PassStep> steps;
      bool any_stage = false;
      for (const std::size_t c : at_depth[depth]) {
        if (rig.components[c].chain.size() <= position) continue;
        any_stage = true;
        for (std::size_t d = c; d < rig.subtree_end[c]; ++d) {
          const auto [first, end] = groups_of(d);
          if (first == end) continue;  // no own vertices
          const std::size_t path_position = applied[d]++;
          const bool last = applied[d] == paths[d].size();
          const PlaneSet target = last                                 ? PlaneSet::kOutput
                                  : location[d] == PlaneSet::kScratchA ? PlaneSet::kScratchB
                                                                       : PlaneSet::kScratchA;
          const RigStage& stage = rig.components[c].chain[position];
          add_step(steps,
                   {first, end, location[d], target, stage_function(stage, path_position == 0),
                    path_position, stage_index(rig, c, position), values_offset(rig, stage),
                    derived_offset(rig, c, position)});
          location[d] = target;
        }
      }
      if (!any_stage) break;
      plan.passes.push_back(std::move(steps));
    }
  }
  for (std::size_t c = 0; c < count && !plan.passes.empty(); ++c) {
    const auto [first, end] = groups_of(c);
    if (paths[c].empty() && first != end) {
      add_step(plan.passes.front(),
               {first, end, PlaneSet::kRest, PlaneSet::kOutput, nullptr, 0, 0, 0});
    }
  }
  for (std::size_t c = 0; c < count; ++c) {
    if (groups_of(c).first == groups_of(c).second) continue;
    plan.scratch_sets = std::max(
        plan.scratch_sets, std::min<std::size_t>(paths[c].empty() ? 0 : paths[c].size() - 1, 2));
  }
  plan.scratch_records_per_slot = scratch_records / double(slots.slot_count);
  return plan;
}

std::vector<FusedLaunch> make_fused_plan(const RiggedMesh& model, const SlotLayout& slots,
                                         std::size_t group_size, bool share_code) {
  const Rig& rig = model.rig();
  std::vector<FusedLaunch> launches;
  if (!share_code) launches.push_back({0, slots.slot_count / group_size, {}, {}});
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    if (slots.first_slot[c + 1] == slots.first_slot[c]) continue;  // no own vertices
    const std::vector<const char*> shape = path_functions(model, c);
    std::size_t end = c + 1;
    while (share_code && end < rig.components.size() &&
           (slots.first_slot[end + 1] == slots.first_slot[end] ||
            path_functions(model, end) == shape)) {
      ++end;
    }
    const std::size_t first_group = slots.first_slot[c] / group_size;
    const std::size_t end_group = slots.first_slot[end] / group_size;
    if (share_code) launches.push_back({first_group, end_group, {}, {}});
    for (std::size_t k = c; k < end; ++k) {
      if (slots.first_slot[k + 1] == slots.first_slot[k]) continue;
      launches.back().branch_ends.push_back(slots.first_slot[k + 1] / group_size);
      launches.back().branch_components.push_back(k);
    }
    c = end - 1;
  }
  return launches;
}

}  // namespace finflex::detail

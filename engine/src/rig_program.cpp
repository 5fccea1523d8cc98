#include "rig_program.hpp"

#include <algorithm>
#include <sstream>

namespace finflex::detail {
namespace {

std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// The kernels/rig.cl function that applies one stage.
const char* stage_function(const RigStage& stage) {
  if (stage.deformer == DeformerKind::kHinge) return "apply_hinge";
  return stage.mode == BendMode::kExact ? "apply_bend_exact" : "apply_bend_paper";
}

// "apply_...(&p, &n, &t, stages + k, values[param]);"
std::string stage_call(const Rig& rig, std::size_t component, std::size_t stage) {
  const RigStage& s = rig.components[component].chain[stage];
  std::ostringstream call;
  call << stage_function(s) << "(&p, &n, &t, stages + " << stage_index(rig, component, stage)
       << ", values[" << s.param << "]);";
  return call.str();
}

// The suffix of kernels/rig.cl's FF_LOAD_* and FF_STORE_* macros for a set.
const char* plane_set_name(PlaneSet set) {
  switch (set) {
    case PlaneSet::kRest:
      return "REST";
    case PlaneSet::kScratchA:
      return "SCRATCH_A";
    case PlaneSet::kScratchB:
      return "SCRATCH_B";
    case PlaneSet::kOutput:
      return "OUTPUT";
  }
  return "REST";
}

}  // namespace

SlotLayout make_slot_layout(const Rig& rig, std::size_t vertex_count, std::size_t group_size) {
  SlotLayout slots;
  slots.slot_of_vertex.assign(vertex_count, 0);
  slots.first_slot.push_back(0);
  for (const RigComponent& component : rig.components) {
    std::size_t slot = slots.first_slot.back();
    for (std::uint32_t v : component.vertices)
      slots.slot_of_vertex[v] = static_cast<std::uint32_t>(slot++);
    slots.first_slot.push_back(round_up(slot, group_size));
  }
  slots.slot_count = std::max(slots.first_slot.back(), group_size);
  slots.vertex_of_slot.assign(slots.slot_count, -1);
  for (std::size_t v = 0; v < vertex_count; ++v)
    slots.vertex_of_slot[slots.slot_of_vertex[v]] = static_cast<std::int64_t>(v);
  return slots;
}

std::size_t stage_index(const Rig& rig, std::size_t component, std::size_t stage) {
  std::size_t index = 0;
  for (std::size_t c = 0; c < component; ++c) index += rig.components[c].chain.size();
  return index + stage;
}

std::size_t stage_count(const Rig& rig) { return stage_index(rig, rig.components.size(), 0); }

std::vector<float> stage_frames(const Rig& rig) {
  const std::size_t count = std::max<std::size_t>(stage_count(rig), 1);
  std::vector<float> table(16 * count, 0.0f);  // a valid (unused) table without stages
  std::size_t k = 0;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      const BodyFrame& f = stage.frame;
      const double values[16] = {f.axis_x.x, f.axis_x.y, f.axis_x.z, 1.0 / f.length,
                                 f.axis_y.x, f.axis_y.y, f.axis_y.z, stage.width,
                                 f.axis_z.x, f.axis_z.y, f.axis_z.z, 0.0,
                                 f.origin.x, f.origin.y, f.origin.z, f.length};
      for (std::size_t c = 0; c < 16; ++c) table[c * count + k] = static_cast<float>(values[c]);
      ++k;
    }
  }
  return table;
}

PassPlan make_pass_plan(const Rig& rig, const SlotLayout& slots, std::size_t group_size) {
  const std::size_t count = rig.components.size();
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> paths(count);
  for (std::size_t c = 0; c < count; ++c) paths[c] = rig.path(c);
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
          previous.target == step.target && previous.applies_stage == step.applies_stage &&
          previous.component == step.component && previous.stage == step.stage) {
        previous.end_group = step.end_group;  // contiguous and alike: one branch
        return;
      }
    }
    steps.push_back(step);
  };

  std::size_t max_depth = 0;
  for (std::size_t c = 0; c < count; ++c) max_depth = std::max(max_depth, rig.depth(c));
  for (std::size_t depth = max_depth + 1; depth-- > 0;) {
    for (std::size_t position = 0;; ++position) {
      std::vector<PassStep> steps;
      bool any_stage = false;
      for (std::size_t c = 0; c < count; ++c) {
        if (rig.depth(c) != depth || rig.components[c].chain.size() <= position) continue;
        any_stage = true;
        for (std::size_t d = c; d < rig.subtree_end[c]; ++d) {
          const auto [first, end] = groups_of(d);
          if (first == end) continue;  // no own vertices
          const bool last = ++applied[d] == paths[d].size();
          const PlaneSet target = last ? PlaneSet::kOutput
                                  : location[d] == PlaneSet::kScratchA ? PlaneSet::kScratchB
                                                                       : PlaneSet::kScratchA;
          add_step(steps, {first, end, location[d], target, true, c, position});
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
      add_step(plan.passes.front(), {first, end, PlaneSet::kRest, PlaneSet::kOutput, false, 0, 0});
    }
  }
  for (std::size_t c = 0; c < count; ++c) {
    if (groups_of(c).first == groups_of(c).second) continue;
    plan.scratch_sets = std::max(plan.scratch_sets, std::min<std::size_t>(
                                                        paths[c].empty() ? 0 : paths[c].size() - 1, 2));
  }
  plan.scratch_records_per_slot = scratch_records / double(slots.slot_count);
  return plan;
}

std::size_t longest_path(const Rig& rig) {
  std::size_t longest = 0;
  for (std::size_t c = 0; c < rig.components.size(); ++c)
    longest = std::max(longest, rig.path(c).size());
  return longest;
}

std::string rig_dispatch_source(const Rig& rig, const SlotLayout& slots, const PassPlan& plan,
                                std::size_t group_size) {
  std::ostringstream out;
  out << "/* Generated for one rig by engine/src/rig_program.cpp: which stages apply to\n"
         " * which work-groups (kernels/rig.cl). */\n";
  out << "#define FF_RIG_STAGE_COUNT " << std::max<std::size_t>(stage_count(rig), 1) << "u\n";
  // Fused: the group's component's whole path, bottom-up.
  out << "#define FF_RIG_FUSED_STAGES";
  const char* keyword = "if";
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    if (slots.first_slot[c + 1] == slots.first_slot[c]) continue;  // no own vertices
    out << " \\\n  " << keyword << " (group < " << slots.first_slot[c + 1] / group_size << "u) {";
    for (const auto& [component, stage] : rig.path(c))
      out << " " << stage_call(rig, component, stage);
    out << " }";
    keyword = "else if";
  }
  out << "\n";
  // Passes: a branch per step, loading from its source set and storing to its target.
  for (std::size_t q = 0; q < plan.passes.size(); ++q) {
    out << "#define FF_RIG_PASS_" << q;
    const char* branch = "if";
    for (const PassStep& step : plan.passes[q]) {
      out << " \\\n  " << branch << " (group >= " << step.first_group << "u && group < "
          << step.end_group << "u) { FF_LOAD_" << plane_set_name(step.source) << " ";
      if (step.applies_stage) out << stage_call(rig, step.component, step.stage) << " ";
      out << "FF_STORE_" << plane_set_name(step.target) << " }";
      branch = "else if";
    }
    out << "\n";
  }
  out << "#define FF_RIG_PASS_KERNELS";
  for (std::size_t q = 0; q < plan.passes.size(); ++q) out << " FF_DEFINE_RIG_PASS(" << q << ")";
  out << "\n";
  return out.str();
}

}  // namespace finflex::detail

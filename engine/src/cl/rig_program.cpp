#include "cl/rig_program.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <sstream>
#include <utility>

#include "cl/device_profile.hpp"
#include "finflex/context.hpp"
#include "finflex/error.hpp"
#include "cl/segment_tables.hpp"

namespace finflex::detail {
namespace {

std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// The deformer's OpenCL function that applies one stage in its frame; for vertices that
// come straight from the rest planes (the stage is first on their path), its rest
// function where it has one (DeformerType::cl_rest_function).
const char* stage_function(const RigStage& stage, bool from_rest) {
  if (from_rest && stage.deformer->cl_rest_function) return stage.deformer->cl_rest_function;
  return stage.deformer->cl_function(stage.options);
}

// Offset of the stage's values in a parameter row.
std::size_t values_offset(const Rig& rig, const RigStage& stage) {
  return rig.parameters[stage.param].offset;
}

// Applies the stage at path position j of the group's path to the vertex; a vertex's
// first stage finds it in its frame already (the rest planes):
// "{ const StageFrame f = ff_stage_table + <k>; [enter_frame(&p, &n, &t, f);]
//    const SecantSample s = <function>(p, f, values + <offset>, derived + <offset>);
//    leave_frame(&p, &n, &t, f, s); }", with <k> and the offsets compiled in
// (`literal`: the group range has one stage there) or read from the path and stage
// tables (FF_PATH_STAGE(j), FF_STAGE_VALUES(f), FF_STAGE_DERIVED(f)). The root's last
// stage leaves with FF_LEAVE_LAST instead (kernels/common/placement.cl: to the world
// when placing).
// Values of a frame link (kernels/common/stage_frame.cl leave_into).
constexpr std::size_t kLinkValues = 21;

struct StageCall {
  const char* function = nullptr;
  std::size_t position = 0;
  bool first = false;  // the vertex is in the stage's frame already
  bool last_of_root = false;
  bool literal = false;
  std::size_t stage = 0;    // stage index, when literal
  std::size_t values = 0;   // values offset, when literal
  std::size_t derived = 0;  // derived values offset, when literal
  // Leaves straight into the next stage's frame through link `link` of ff_link_table
  // (frame_links; read from the path table's link rows when not literal), when not the
  // path's last stage; else kNoLink.
  std::size_t link = kNoLink;
  static constexpr std::size_t kNoLink = ~std::size_t{0};
};

// `more_arguments`: after the stage function's own (a swept function's: swept_arguments).
std::string stage_call(const StageCall& c, const std::string& more_arguments = "") {
  std::ostringstream call;
  call << "{ const StageFrame f = ff_stage_table + ";
  if (c.literal) {
    call << c.stage << "; ";
  } else {
    call << "FF_PATH_STAGE(" << c.position << "); ";
  }
  if (!c.first) call << "enter_frame(&p, &n, &t, f); ";
  call << "const SecantSample s = " << c.function << "(p, f, values + ";
  if (c.literal) {
    call << c.values << ", derived + " << c.derived;
  } else {
    call << "FF_STAGE_VALUES(f), derived + FF_STAGE_DERIVED(f)";
  }
  call << more_arguments << "); ";
  if (c.link != StageCall::kNoLink && c.literal) {
    call << "leave_into(&p, &n, &t, ff_link_table + " << kLinkValues * c.link << ", s);";
  } else if (c.link != StageCall::kNoLink) {
    call << "leave_into(&p, &n, &t, ff_link_table + " << kLinkValues << " * FF_PATH_LINK("
         << c.position << "), s);";
  } else {
    call << (c.last_of_root ? "FF_LEAVE_LAST(f, s)" : "leave_frame(&p, &n, &t, f, s);");
  }
  call << " }";
  return call.str();
}

// The functions along component c's path: its code shape.
std::vector<const char*> path_functions(const RiggedMesh& model, std::size_t c) {
  std::vector<const char*> functions;
  for (const StageRef& ref : model.paths()[c])
    functions.push_back(stage_function(model.rig().stage(ref), functions.empty()));
  return functions;
}

// A stage's derived values, rounded up to 8 floats: every stage's start 32-byte
// aligned (DeformerType::derived_count), and so every instance's row.
std::size_t aligned_derived(const RigStage& stage) {
  return round_up(stage.deformer->derived_count(stage.options), 8);
}

// Derived values before stage k (stages in rig order).
std::size_t derived_offset_of(const Rig& rig, std::size_t k) {
  std::size_t offset = 0, index = 0;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      if (index++ == k) return offset;
      if (stage.deformer->derived_count) offset += aligned_derived(stage);
    }
  }
  return offset;
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

// The first stage on the component's path (its own chain, then its ancestors') that
// looks vertices up in a table along x (a deformer with derived values), or null.
const RigStage* first_table_stage(const Rig& rig, std::size_t component) {
  // A resolved rig is a tree: the walk up ends within the component count.
  for (std::size_t steps = 0; steps < rig.components.size(); ++steps) {
    const RigComponent& on_path = rig.components[component];
    for (const RigStage& stage : on_path.chain) {
      if (stage.deformer->derived_count != nullptr) return &stage;
    }
    if (on_path.parent < 0) break;
    component = static_cast<std::size_t>(on_path.parent);
  }
  return nullptr;
}

// The component's vertices in slot order: by rest x in the frame of the first table
// stage on its path (ties by vertex index), else as they are (ascending). A fin under
// a spine is sorted along the spine too: its vertices reach the spine's table after
// its own hinge, which moves them little along the body.
std::vector<std::uint32_t> vertices_in_slot_order(const Rig& rig, std::size_t component,
                                                  const std::vector<glm::vec3>& positions) {
  std::vector<std::uint32_t> order = rig.components[component].vertices;
  const RigStage* table = first_table_stage(rig, component);
  if (table == nullptr) return order;
  std::vector<std::pair<double, std::uint32_t>> keyed;
  keyed.reserve(order.size());
  for (std::uint32_t v : order) {
    keyed.emplace_back(table->frame.point_to_local(glm::dvec3(positions[v])).x, v);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

SlotLayout make_slot_layout(const Rig& rig, const std::vector<glm::vec3>& positions,
                            std::size_t group_size) {
  const std::size_t vertex_count = positions.size();
  SlotLayout slots;
  slots.slot_of_vertex.assign(vertex_count, 0);
  slots.first_slot.push_back(0);
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    std::size_t slot = slots.first_slot.back();
    for (std::uint32_t v : vertices_in_slot_order(rig, c, positions))
      slots.slot_of_vertex[v] = static_cast<std::uint32_t>(slot++);
    slots.first_slot.push_back(round_up(slot, group_size));
  }
  slots.slot_count = std::max(slots.first_slot.back(), group_size);
  if (slots.slot_count > 0xffffffffu) {
    throw Error(ErrorCode::kInvalidMesh, "positions",
                "the mesh needs " + std::to_string(slots.slot_count) +
                    " vertex slots, more than the kernels' 2^32");
  }
  slots.vertex_of_slot.assign(slots.slot_count, -1);
  for (std::size_t v = 0; v < vertex_count; ++v)
    slots.vertex_of_slot[slots.slot_of_vertex[v]] = static_cast<std::int64_t>(v);
  return slots;
}

RestPlanes make_rest_planes(const RiggedMesh& model, const SlotLayout& slots) {
  const Rig& rig = model.rig();
  const Mesh& mesh = model.mesh();
  RestPlanes rest;
  const std::size_t n = slots.slot_count;
  rest.positions.assign(3 * n, 0.0f);
  rest.normals.assign(3 * n, 0.0f);
  if (mesh.has_tangents()) rest.tangents.assign(4 * n, 0.0f);  // x, y, z, handedness
  auto put = [n](std::vector<float>& planes, std::size_t slot, const glm::dvec3& value) {
    for (int c = 0; c < 3; ++c) planes[static_cast<std::size_t>(c) * n + slot] = float(value[c]);
  };
  for (std::size_t slot = 0; slot < n; ++slot) {  // padding: harmless values
    put(rest.normals, slot, glm::dvec3(0.0, 0.0, 1.0));
    if (!rest.tangents.empty()) {
      put(rest.tangents, slot, glm::dvec3(1.0, 0.0, 0.0));
      rest.tangents[3 * n + slot] = 1.0f;
    }
  }
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    const BodyFrame first = path.empty() ? BodyFrame::identity() : rig.stage(path.front()).frame;
    for (std::uint32_t v : rig.components[c].vertices) {
      const std::size_t slot = slots.slot_of_vertex[v];
      // (2): p = R (p_b - origin) / s_x, n = R n_b, in double before rounding.
      put(rest.positions, slot, first.point_to_local(glm::dvec3(mesh.positions[v])));
      put(rest.normals, slot, first.vector_to_local(glm::normalize(glm::dvec3(mesh.normals[v]))));
      if (!rest.tangents.empty()) {
        put(rest.tangents, slot,
            first.vector_to_local(glm::normalize(glm::dvec3(mesh.tangents[v]))));
        rest.tangents[3 * n + slot] = mesh.tangents[v].w;
      }
    }
    // The component's padding repeats its last slot's position, so that its slots stay
    // sorted by x where they are (make_slot_layout; DeformerType::cl_rest_function).
    const std::size_t count = rig.components[c].vertices.size();
    for (std::size_t slot = slots.first_slot[c] + count;
         count > 0 && slot < slots.first_slot[c + 1]; ++slot) {
      for (std::size_t axis = 0; axis < 3; ++axis)
        rest.positions[axis * n + slot] = rest.positions[axis * n + slot - 1];
    }
  }
  return rest;
}

std::size_t stage_index(const Rig& rig, std::size_t component, std::size_t stage) {
  std::size_t index = 0;
  for (std::size_t c = 0; c < component; ++c) index += rig.components[c].chain.size();
  return index + stage;
}

std::size_t stage_count(const Rig& rig) { return stage_index(rig, rig.components.size(), 0); }

std::size_t derived_per_instance(const Rig& rig) {
  return derived_offset_of(rig, stage_count(rig));
}

std::size_t derived_offset(const Rig& rig, std::size_t component, std::size_t stage) {
  return derived_offset_of(rig, stage_index(rig, component, stage));
}

std::size_t stage_table_rows(const Rig& rig) { return stage_count(rig) + 1; }

std::vector<float> stage_table(const Rig& rig) {
  const std::size_t count = stage_table_rows(rig);
  std::vector<float> table(kStageValues * count, 0.0f);
  // A row per stage, in rig order, then the root's frame (for placing from mesh
  // coordinates when the root has no stage).
  std::vector<const RigStage*> rows;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) rows.push_back(&stage);
  }
  RigStage root;
  root.frame = rig.components.front().frame;
  rows.push_back(&root);
  for (std::size_t k = 0; k < count; ++k) {
    const RigStage& stage = *rows[k];
    const BodyFrame& f = stage.frame;
    const StageConstants c = stage.deformer
                                 ? stage.deformer->stage_constants(stage.options, stage.geometry)
                                 : StageConstants{};
    const double offset = stage.deformer ? double(values_offset(rig, stage)) : 0.0;
    const double derived = double(derived_offset_of(rig, k));
    // kernels/common/stage_frame.cl's layout.
    // clang-format off
    const double values[kStageValues] = {
        f.axis_x.x, f.axis_x.y, f.axis_x.z, 1.0 / f.length,   // 0-3
        f.axis_y.x, f.axis_y.y, f.axis_y.z, c[0],             // 4-7
        f.axis_z.x, f.axis_z.y, f.axis_z.z, offset,           // 8-11
        f.origin.x, f.origin.y, f.origin.z, f.length,         // 12-15
        c[1], c[2], c[3], derived};                           // 16-19
    // clang-format on
    for (std::size_t v = 0; v < kStageValues; ++v)
      table[v * count + k] = static_cast<float>(values[v]);
  }
  return table;
}

// A program-scope OpenCL constant array of `values`, `per_line` to a line; hexadecimal
// literals keep every float exact.
std::string constant_array_source(const char* name, const std::vector<float>& values,
                                  std::size_t per_line) {
  std::ostringstream out;
  out << "__constant float " << name << "[" << values.size() << "] = {" << std::hexfloat;
  for (std::size_t i = 0; i < values.size(); ++i) {
    out << (i % per_line == 0 ? "\n  " : " ") << values[i] << "f,";
  }
  out << "};\n";
  return out.str();
}

// The stage table as a program-scope constant array (kernels/common/stage_frame.cl):
// a frame's values fold into the instructions that use them, where a table in a
// buffer costs a load each (NVIDIA's OpenCL reads __constant arguments as global
// memory).
std::string stage_table_source(const Rig& rig) {
  return constant_array_source("ff_stage_table", stage_table(rig), 4);
}

// The frames of the stage table's rows, in its order: the stages in rig order, then
// the root's frame.
std::vector<BodyFrame> stage_frames(const Rig& rig) {
  std::vector<BodyFrame> frames;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) frames.push_back(stage.frame);
  }
  frames.push_back(rig.components.front().frame);
  return frames;
}

// From frame a straight into frame b, the two transforms of (2) composed (in double,
// rounded once): point_into(point_out_of(p, a), b) = (s_a / s_b) M p + c and
// rotate_into(rotate_out_of(d, a), b) = M d, with M = R_b R_a^T and
// c = R_b (o_a - o_b) / s_b (R's rows: the frame's axes). kernels/common/stage_frame.cl's
// layout: 0-8 (s_a / s_b) M, 9-11 c, 12-20 M, row-major.
std::array<float, kLinkValues> link_values(const BodyFrame& a, const BodyFrame& b) {
  const glm::dvec3 axes_a[3] = {a.axis_x, a.axis_y, a.axis_z};
  const glm::dvec3 axes_b[3] = {b.axis_x, b.axis_y, b.axis_z};
  const double scale = a.length / b.length;
  std::array<float, kLinkValues> values{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const double m = glm::dot(axes_b[r], axes_a[c]);
      values[3 * r + c] = static_cast<float>(scale * m);
      values[12 + 3 * r + c] = static_cast<float>(m);
    }
    values[9 + r] = static_cast<float>(glm::dot(axes_b[r], a.origin - b.origin) / b.length);
  }
  return values;
}

// The links a fused path takes, from stage `from` into stage `to` (stage indices), as
// the program-scope constant array ff_link_table (nothing when there are none).
std::string link_table_source(const Rig& rig, const FrameLinks& links) {
  if (links.pairs.empty()) return "";
  const std::vector<BodyFrame> frames = stage_frames(rig);
  std::vector<float> values;
  for (const auto& [from, to] : links.pairs) {
    const std::array<float, kLinkValues> link = link_values(frames[from], frames[to]);
    values.insert(values.end(), link.begin(), link.end());
  }
  return constant_array_source("ff_link_table", values, 7);
}

std::vector<std::string> rig_program_files(const Rig& rig) {
  std::vector<std::string> files = common_kernel_files();
  for (const DeformerType* type : deformer_types()) {
    bool used = false;
    for (const RigComponent& component : rig.components) {
      for (const RigStage& stage : component.chain) used = used || stage.deformer == type;
    }
    if (used) files.push_back(type->cl_file);
  }
  files.push_back("rig.cl");
  return files;
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

std::string prepare_items_source(std::size_t items) {
  return "#define FF_PREPARE_ITEMS " + std::to_string(items) + "\n#define FF_PREPARE_GROUP_SIZE " +
         std::to_string(table_group_size(items)) + "\n#define FF_PREPARE_BARRIER() " +
         (items > 1 ? "barrier(CLK_LOCAL_MEM_FENCE)" : "/* one work-item */") + "\n";
}

std::string rig_dispatch_source(const RiggedMesh& model, const SlotLayout& slots,
                                const RestPlanes& rest, const std::vector<FusedLaunch>& fused,
                                const PassPlan& plan, std::size_t group_size,
                                std::size_t prepare_items, bool share_code, bool lane_tables) {
  const Rig& rig = model.rig();
  std::ostringstream out;
  out << "/* Generated for one rig by engine/src/rig_program.cpp: which stages apply to\n"
         " * which work-groups (kernels/rig.cl). */\n";
  out << "#define FF_STAGE_COUNT " << stage_table_rows(rig) << "u\n";
  out << stage_table_source(rig);
  SweptSegments swept;
  swept.first_entry.assign(rig.components.size(), SweptSegments::kNone);
  if (lane_tables) {
    swept = swept_segments(model, slots);
    out << segment_tables_source(slot_segments(model, slots, rest), swept);
  }
  const bool root_has_stages = !rig.components.front().chain.empty();
  if (!root_has_stages) out << "#define FF_ROOT_FRAME " << stage_count(rig) << "u\n";
  out << "#define FF_RIG_GROUP_COUNT " << slots.slot_count / group_size << "u\n";
  out << "#define FF_PATH_WIDTH " << path_table_width(model) << "u\n";
  out << prepare_items_source(prepare_items);
  // Fused: the group's component's whole path, bottom-up; a kernel per launch, a branch
  // per run of components in it (none when the launch has one).
  // A vertex leaves each stage but its path's last straight into the next one's frame
  // (a link, frame_links).
  const FrameLinks links = frame_links(model);
  // Component c's whole path, bottom-up, its stages compiled in (literal) or read from
  // the path and stage tables.
  auto path_code = [&](std::size_t c, bool literal) {
    std::ostringstream code;
    const std::vector<const char*> shape = path_functions(model, c);
    const std::vector<StageRef>& path = model.paths()[c];
    bool linked_in = false;
    for (std::size_t j = 0; j < path.size(); ++j) {
      StageCall call{shape[j],
                     j,
                     j == 0 || linked_in,
                     root_has_stages && j + 1 == path.size(),
                     literal,
                     stage_index(rig, path[j].component, path[j].stage),
                     values_offset(rig, rig.stage(path[j])),
                     derived_offset(rig, path[j].component, path[j].stage)};
      linked_in = j + 1 < path.size();
      if (linked_in) call.link = links.of_path[c][j];
      // The last stage of a component with swept segments (segment_tables.hpp), compiled in.
      std::string more_arguments;
      if (literal && j + 1 == path.size() && swept.first_entry[c] != SweptSegments::kNone) {
        call.function = rig.stage(path[j]).deformer->cl_swept_function;
        more_arguments = swept_arguments(swept, slots, c);
      }
      code << " " << stage_call(call, more_arguments);
    }
    return code.str();
  };
  // A branch per component (none when there is one), each path compiled in.
  auto branches_code = [&](const std::vector<std::size_t>& components,
                           const std::vector<std::size_t>& ends) {
    std::ostringstream code;
    for (std::size_t b = 0; b < components.size(); ++b) {
      code << " \\\n  ";
      if (components.size() > 1) {
        code << (b == 0 ? "if" : "else if") << " (group < " << ends[b] << "u) ";
      }
      code << "{" << path_code(components[b], true) << " }";
    }
    return code.str();
  };
  std::ostringstream macros;
  if (share_code) {
    // Kernels of more than one lane are vector code already: one kernel, rig_fused_0,
    // over every work-group, a branch per component with its stages compiled in (the
    // host launches it once: ClDeformer::Impl::enqueue). A CPU thread then runs
    // fins, whose arithmetic is two to four times a body vertex's, while other threads' body
    // work-groups wait on memory: 2.26 -> 2.03 ms a frame for 1,000 swimming fish on 16
    // PoCL threads, alike or a little slower on 2 (docs/benchmarks.md).
    std::vector<std::size_t> components, ends;
    for (const FusedLaunch& launch : fused) {
      components.insert(components.end(), launch.branch_components.begin(),
                        launch.branch_components.end());
      ends.insert(ends.end(), launch.branch_ends.begin(), launch.branch_ends.end());
    }
    macros << "#if FF_LANES > 1\n#define FF_RIG_FUSED_0" << branches_code(components, ends)
           << "\n#define FF_RIG_FUSED_KERNELS FF_DEFINE_RIG_FUSED(0)\n#else\n";
    // Shared code for the one-lane kernels, a kernel per launch (PoCL's work-group
    // vectoriser wants straight-line kernels).
    for (std::size_t r = 0; r < fused.size(); ++r) {
      macros << "#define FF_RIG_FUSED_" << r << " \\\n  {"
             << path_code(fused[r].branch_components.front(), false) << " }\n";
    }
  } else {
    for (std::size_t r = 0; r < fused.size(); ++r) {
      macros << "#define FF_RIG_FUSED_" << r
             << branches_code(fused[r].branch_components, fused[r].branch_ends) << "\n";
    }
  }
  macros << "#define FF_RIG_FUSED_KERNELS";
  for (std::size_t r = 0; r < fused.size(); ++r) macros << " FF_DEFINE_RIG_FUSED(" << r << ")";
  macros << (share_code ? "\n#endif\n" : "\n");
  out << link_table_source(rig, links) << macros.str();
  // Passes: a branch per step, loading from its source set and storing to its target.
  for (std::size_t q = 0; q < plan.passes.size(); ++q) {
    out << "#define FF_RIG_PASS_" << q;
    const char* branch = "if";
    for (const PassStep& step : plan.passes[q]) {
      out << " \\\n  " << branch << " (group >= " << step.first_group << "u && group < "
          << step.end_group << "u) { FF_LOAD_" << plane_set_name(step.source) << " ";
      if (step.function) {
        const StageCall call{step.function,
                             step.path_position,
                             step.source == PlaneSet::kRest,
                             root_has_stages && step.target == PlaneSet::kOutput,
                             !share_code,
                             step.stage,
                             step.values,
                             step.derived};
        out << stage_call(call) << " ";
      }
      out << "FF_STORE_" << plane_set_name(step.target) << " }";
      branch = "else if";
    }
    out << "\n";
  }
  out << "#define FF_RIG_PASS_KERNELS";
  for (std::size_t q = 0; q < plan.passes.size(); ++q) out << " FF_DEFINE_RIG_PASS(" << q << ")";
  out << "\n";
  // Derived values: each stage's prepare function, on every instance.
  out << "#define FF_RIG_PREPARE";
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    for (std::size_t k = 0; k < rig.components[c].chain.size(); ++k) {
      const RigStage& stage = rig.components[c].chain[k];
      if (!stage.deformer->cl_prepare_function) continue;
      out << " \\\n  " << stage.deformer->cl_prepare_function << "(values + "
          << values_offset(rig, stage) << ", derived + " << derived_offset(rig, c, k)
          << ", ff_stage_table + " << stage_index(rig, c, k) << ", scratch, item);";
    }
  }
  out << "\n";
  return out.str();
}

}  // namespace finflex::detail

#include "cl/rig_source.hpp"

#include <array>
#include <sstream>

#include "cl/device_profile.hpp"
#include "cl/segment_tables.hpp"
#include "finflex/context.hpp"

namespace finflex::detail {
namespace {

// Values of a frame link (kernels/common/stage_frame.cl leave_into).
constexpr std::size_t kLinkValues = 21;

// A stage's code: it applies the stage at path position j of the group's path to the
// vertex; a vertex's first stage finds it in its frame already (the rest planes):
// "{ const StageFrame f = ff_stage_table + <k>; [enter_frame(&p, &n, &t, f);]
//    const SecantSample s = <function>(p, f, values + <offset>, derived + <offset>);
//    leave_frame(&p, &n, &t, f, s); }", with <k> and the offsets compiled in
// (`literal`: the group range has one stage there) or read from the path and stage
// tables (FF_PATH_STAGE(j), FF_STAGE_VALUES(f), FF_STAGE_DERIVED(f)). The root's last
// stage leaves with FF_LEAVE_LAST instead (kernels/common/placement.cl: to the world
// when placing).
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

}  // namespace

std::string stage_table_source(const Rig& rig) {
  return constant_array_source("ff_stage_table", stage_table(rig), 4);
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
  out << "/* Generated for one rig by engine/src/cl/rig_source.cpp: which stages apply to\n"
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
    // host launches it once: ClDeformer::Impl::enqueue), so a CPU thread runs fins
    // while other threads' body work-groups wait on memory
    // (docs/benchmarks.md#choice-dispatch).
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

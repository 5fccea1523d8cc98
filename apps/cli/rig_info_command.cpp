// finflex rig-info: what a rig file selects on a mesh, for writing and checking rigs.
// Prints every component (parent, vertices, frame, stages and their parameters'
// valid ranges); --labels writes one line per mesh vertex: its component and its
// position in the root's body frame. Then the mesh's levels of detail (--levels,
// --triangle-ratio): each level's vertices, triangles and geometric error.
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <utility>

#include "atomic_file.hpp"
#include "cli_errors.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "level_flags.hpp"

namespace finflex::cli {
namespace {

struct RigInfoOptions {
  std::string in;
  std::string rig;
  std::string labels;
  std::string levels = "4";
  std::string triangle_ratio = "0.25";
  bool freeze_fins = true;
};

void print_frame(const BodyFrame& f) {
  std::printf(
      "    frame: origin (%.4f, %.4f, %.4f), x (%.4f, %.4f, %.4f), y (%.4f, %.4f, %.4f), length "
      "%.4f\n",
      f.origin.x, f.origin.y, f.origin.z, f.axis_x.x, f.axis_x.y, f.axis_x.z, f.axis_y.x,
      f.axis_y.y, f.axis_y.z, f.length);
}

// Written to a temporary file and renamed into place: on any error an existing labels
// file is left as it was and no temporary file remains.
void write_labels(const std::string& path, const Mesh& mesh, const Rig& rig) {
  std::vector<std::size_t> component_of(mesh.vertex_count(), 0);
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    for (std::uint32_t v : rig.components[c].vertices) component_of[v] = c;
  }
  write_file_atomically("--labels", path, [&](std::ostream& out) {
    out << "# component x y z  (one line per mesh vertex; x y z in the root's body frame)\n";
    const BodyFrame& root = rig.components.front().frame;
    char line[1024];  // three %.6f of any double (at most 317 characters each)
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::dvec3 p = root.point_to_local(glm::dvec3(mesh.positions[v]));
      std::snprintf(line, sizeof line, " %.6f %.6f %.6f\n", p.x, p.y, p.z);
      out << rig.components[component_of[v]].name << line;
    }
  });
}

void check_rig_info(const RigInfoOptions& options) {
  check_input_file("--in", options.in, mesh_extensions());
  check_input_file("--rig", options.rig);
  if (!options.labels.empty()) check_output_file("--labels", options.labels);
  parse_level_options(options.levels, options.triangle_ratio);
}

int run_rig_info(const RigInfoOptions& options) {
  try {
    const Mesh mesh = for_option("--in", [&] { return load_mesh(options.in); });
    Rig rig = resolve_rig(for_option("--rig", [&] { return load_rig_file(options.rig); }), mesh);
    std::printf("rig %s on %s (%zu vertices): %zu components, %zu parameters\n",
                options.rig.c_str(), options.in.c_str(), mesh.vertex_count(), rig.components.size(),
                rig.parameters.size());
    for (std::size_t c = 0; c < rig.components.size(); ++c) {
      const RigComponent& component = rig.components[c];
      std::size_t subtree = 0;
      for (std::size_t d = c; d < rig.subtree_end[c]; ++d)
        subtree += rig.components[d].vertices.size();
      std::printf("  %s (parent %s, depth %zu): %zu own vertices, %zu with its descendants\n",
                  component.name.c_str(),
                  component.parent < 0 ? "none" : rig.components[component.parent].name.c_str(),
                  rig.depth(c), component.vertices.size(), subtree);
      print_frame(component.frame);
      for (const RigStage& stage : component.chain) {
        const RigParameter& parameter = rig.parameters[stage.param];
        const std::string settings = describe_options(*stage.deformer, stage.options);
        std::printf("    stage: %s%s%s, parameter %s", stage.deformer->name,
                    settings.empty() ? "" : " ", settings.c_str(), parameter.name.c_str());
        if (parameter.count > 1) std::printf(" (%zu values)", parameter.count);
        std::printf(" in [%.4f, %.4f]\n", -parameter.limit, parameter.limit);
      }
    }
    if (!options.labels.empty()) write_labels(options.labels, mesh, rig);
    const double length = rig.components.front().frame.length;
    const RiggedMesh model(mesh, std::move(rig));
    print_levels(for_option("--levels",
                            [&] {
                              return make_detail_levels(
                                  model,
                                  frozen_fin_bounds(
                                      parse_level_options(options.levels, options.triangle_ratio,
                                                          options.freeze_fins),
                                      model));
                            }),
                 length);
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("rig-info", error.what());
  }
}

}  // namespace

Command add_rig_info_command(CLI::App& app) {
  auto options = std::make_shared<RigInfoOptions>();
  CLI::App* command = app.add_subcommand("rig-info", "Show what a rig selects on a mesh");
  command->add_option("--in", options->in, "Mesh")->required();
  command->add_option("--rig", options->rig, "Rig file (JSON)")->required();
  command->add_option("--labels", options->labels,
                      "Write each vertex's component and body-frame position to this file");
  command
      ->add_option("--levels", options->levels,
                   "Levels of detail to make and report, the full mesh included (1-8)")
      ->capture_default_str();
  command
      ->add_option("--triangle-ratio", options->triangle_ratio,
                   "Each level's triangles as a fraction of the finer level's")
      ->capture_default_str();
  command->add_flag(kFreezeFinsFlag, options->freeze_fins, kFreezeFinsHelp);
  return {[options] { check_rig_info(*options); }, [options] { return run_rig_info(*options); }};
}

}  // namespace finflex::cli

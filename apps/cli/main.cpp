// finflex: deform fish meshes with the secant-surface bend on any OpenCL device.
//
//   finflex deform --in PATH --out PATH --m VALUE [--mode paper|exact]
//                  [--normals rotate|jacobian] [--frame auto|identity] [--clamp] [--device NAME]
//   finflex check --in PATH [--device NAME]
//   finflex rig-info --in PATH --rig RIG.json [--labels FILE]
//   finflex bench --mesh PATH --instances N --frames F [--mode paper|exact]
//                 [--rig RIG.json [--path fused|passes]] [--device NAME] [--json]
//   finflex subdivide --in PATH --levels N --out PATH
//   finflex swim [--fish N] [--seconds S] ... [--out DIR [--annotate]]
//   finflex bake --out DIR [--species MESH:RIG] [--frames N] ...
//   finflex info
#include <iostream>

#include "cli_errors.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace finflex::cli;
  CLI::App app{"FinFlex: secant-surface deformation of fish meshes in OpenCL"};
  app.require_subcommand(1);
  const Command deform = add_deform_command(app);
  const Command check = add_check_command(app);
  const Command rig_info = add_rig_info_command(app);
  const Command bench = add_bench_command(app);
  const Command subdivide = add_subdivide_command(app);
  const Command swim = add_swim_command(app);
  const Command bake = add_bake_command(app);
  const Command info = add_info_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    const std::string command =
        app.get_subcommands().empty() ? std::string("") : app.get_subcommands().front()->get_name();
    return fail(command.empty() ? "" : command, error.what());
  }
  if (app.got_subcommand("deform")) return deform();
  if (app.got_subcommand("check")) return check();
  if (app.got_subcommand("rig-info")) return rig_info();
  if (app.got_subcommand("bench")) return bench();
  if (app.got_subcommand("subdivide")) return subdivide();
  if (app.got_subcommand("swim")) return swim();
  if (app.got_subcommand("bake")) return bake();
  return info();
}

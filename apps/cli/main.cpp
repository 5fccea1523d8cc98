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
#include <exception>
#include <string>

#include "cli_errors.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace finflex::cli;
  CLI::App app{"FinFlex: secant-surface deformation of fish meshes in OpenCL"};
  app.require_subcommand(1);
  const auto commands = add_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    const std::string command =
        app.get_subcommands().empty() ? std::string("") : app.get_subcommands().front()->get_name();
    return fail(command, error.what());
  }
  for (const auto& [name, command] : commands) {
    if (!app.got_subcommand(name)) continue;
    try {
      command.check();  // every option, before any file is read
    } catch (const std::exception& error) {
      return fail(name, error.what());
    }
    return command.run();
  }
  return fail("", "no command given");
}

#include "commands.hpp"

#include <exception>
#include <string>

#include "cli_errors.hpp"
#include "tool.hpp"

namespace finflex::cli {

std::vector<std::pair<std::string, Command>> add_commands(CLI::App& app) {
  std::vector<std::pair<std::string, Command>> commands;
  commands.emplace_back("deform", add_deform_command(app));
  commands.emplace_back("check", add_check_command(app));
  commands.emplace_back("rig-info", add_rig_info_command(app));
  commands.emplace_back("bench", add_bench_command(app));
  commands.emplace_back("subdivide", add_subdivide_command(app));
  commands.emplace_back("swim", add_swim_command(app));
  commands.emplace_back("bake", add_bake_command(app));
  commands.emplace_back("info", add_info_command(app));
  return commands;
}

int run_tool(int argc, char** argv) {
  CLI::App app{"FinFlex: secant-surface deformation of fish meshes in OpenCL"};
  app.set_version_flag("--version", std::string("finflex ") + FINFLEX_VERSION);
  app.require_subcommand(1);
  const auto commands = add_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
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

}  // namespace finflex::cli

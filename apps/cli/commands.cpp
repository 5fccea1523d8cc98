#include "commands.hpp"

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

}  // namespace finflex::cli

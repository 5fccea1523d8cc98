// Subcommands of the finflex tool. Each registers its options on the CLI11 app and
// returns how to check them and how to run it.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace finflex::cli {

struct Command {
  // Checks every option that can be checked without reading a file: numbers, choices,
  // combinations, and what the paths name (an input must be a regular file, an
  // output's folder must exist). Throws finflex::Error naming the option.
  std::function<void()> check;
  // Runs the command (check() first), returning the process exit code; errors are
  // reported as one line (cli_errors.hpp).
  std::function<int()> run;
};

Command add_deform_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_check_command(CLI::App& app);
Command add_rig_info_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_subdivide_command(CLI::App& app);
Command add_swim_command(CLI::App& app);
Command add_bake_command(CLI::App& app);

// Every subcommand, registered on `app` in the order of `finflex --help`, by name.
std::vector<std::pair<std::string, Command>> add_commands(CLI::App& app);

}  // namespace finflex::cli

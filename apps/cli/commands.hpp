// Subcommands of the finflex tool. Each registers its options on the CLI11 app and
// returns the function that runs it (returning the process exit code).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace finflex::cli {

using Command = std::function<int()>;

Command add_deform_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_check_command(CLI::App& app);
Command add_rig_info_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_subdivide_command(CLI::App& app);
Command add_swim_command(CLI::App& app);
Command add_bake_command(CLI::App& app);

}  // namespace finflex::cli

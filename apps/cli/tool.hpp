// The finflex tool as a function (main.cpp calls it), declared apart from commands.hpp
// so that its callers need not compile the command-line parser (CLI11).
#pragma once

namespace finflex::cli {

// Parses `argv`, checks the chosen command's options, runs it; returns the process exit
// code (errors as one line on stderr: cli_errors.hpp).
int run_tool(int argc, char** argv);

}  // namespace finflex::cli

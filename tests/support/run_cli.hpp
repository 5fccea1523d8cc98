// The finflex tool as other programs call it, for the command-line tests: a run's exit
// code, standard output and standard error. Needs FINFLEX_CLI_PATH (tests/CMakeLists.txt
// defines it for every tests/test_cli*.cpp).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

namespace finflex::test {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs the tool with `arguments`; `environment` ("NAME=value ...") goes before it.
inline RunResult run_cli(const std::string& arguments, const std::string& environment = "") {
  const std::string out_path = temp_path("stdout.txt");
  const std::string err_path = temp_path("stderr.txt");
  const std::string command = std::string("POCL_CACHE_DIR=") + FINFLEX_TEST_POCL_CACHE + " " +
                              environment + " '" + FINFLEX_CLI_PATH + "' " + arguments + " >'" +
                              out_path + "' 2>'" + err_path + "' </dev/null";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_text(out_path);
  result.err = read_text(err_path);
  return result;
}

// A bundled fish's path, quoted for the shell.
inline std::string fish(const char* relative) { return "'" + data_path(relative) + "'"; }

inline int line_count(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace finflex::test

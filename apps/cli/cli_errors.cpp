#include "cli_errors.hpp"

#include <iostream>

#include "finflex/error.hpp"

namespace finflex::cli {

int fail(const std::string& command, const std::string& message) {
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::cerr << "finflex" << (command.empty() ? "" : " " + command) << ": error: " << line
            << std::endl;
  return kExitFailure;
}

}  // namespace finflex::cli

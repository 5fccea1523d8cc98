#include "cli_errors.hpp"

#include <cstdlib>
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

double parse_number(const std::string& text, const std::string& option) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size()) {
    throw Error(ErrorCode::kInvalidArgument, option, option + " '" + text + "' is not a number");
  }
  return value;
}

}  // namespace finflex::cli

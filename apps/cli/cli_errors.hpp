// The command-line error contract: exit 0 on success; on bad input or a failure,
// exit 2 with one line on stderr naming the problem.
#pragma once

#include <string>

#include "finflex/error.hpp"

namespace finflex::cli {

constexpr int kExitSuccess = 0;
constexpr int kExitFailure = 2;

// Prints "finflex <command>: error: <message>" as one line (newlines in the message,
// e.g. from an OpenCL build log, become spaces) and returns kExitFailure.
int fail(const std::string& command, const std::string& message);

// Runs `operation`; a finflex::Error it throws comes out with `option` as its field
// and "<option>: " in front of its message, so the user sees which option gave the
// value the library refused.
template <typename Operation>
auto for_option(const std::string& option, Operation operation) {
  try {
    return operation();
  } catch (const Error& error) {
    throw Error(error.code(), option, option + ": " + error.what());
  }
}

}  // namespace finflex::cli

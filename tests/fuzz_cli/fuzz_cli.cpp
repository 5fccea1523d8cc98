// libFuzzer: bytes as a finflex command line (arguments separated by NUL bytes, at
// most 64) through the tool's parser and the chosen subcommand's option checks, the
// part that runs before any file is read. CLI11's and FinFlex's errors are the
// expected outcomes of bad arguments; a crash, a sanitizer report, another exception
// or a hang is a finding. Paths are only looked at (stat), never opened or written.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "commands.hpp"
#include "finflex/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> arguments = {"finflex"};
  std::string current;
  for (std::size_t k = 0; k < size && arguments.size() <= 64; ++k) {
    if (data[k] == 0) {
      arguments.push_back(current);
      current.clear();
    } else {
      current += static_cast<char>(data[k]);
    }
  }
  if (!current.empty() && arguments.size() <= 64) arguments.push_back(current);
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());

  CLI::App app{"finflex"};
  app.require_subcommand(1);
  const auto commands = finflex::cli::add_commands(app);
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
    for (const auto& [name, command] : commands) {
      if (app.got_subcommand(name)) command.check();
    }
  } catch (const CLI::Error&) {
  } catch (const finflex::Error&) {
  }
  return 0;
}

// The command line against hostile arguments: numbers that would wrap or are huge,
// paths that name FIFOs, devices or folders, option errors behind unreadable files,
// and the atomic --labels file. Each case ends within a time limit with exit 2 and
// one line naming the option and the value as typed, and leaves the file system as
// it was.
#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace finflex {
namespace {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string read_text(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs the tool with `arguments` under a 30 s limit (exit 124 past it: a hang), after
// `shell_prefix` (e.g. limits set with ulimit) in bash.
RunResult run_cli(const std::string& arguments, const std::string& shell_prefix = "") {
  const std::string out_path = test::temp_path("stdout.txt");
  const std::string err_path = test::temp_path("stderr.txt");
  const std::string inner = shell_prefix + " POCL_CACHE_DIR=" + FINFLEX_TEST_POCL_CACHE +
                            " timeout 30 '" + FINFLEX_CLI_PATH + "' " + arguments + " >'" +
                            out_path + "' 2>'" + err_path + "' </dev/null";
  std::string quoted;  // for bash -c '...'
  for (const char c : inner) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const int status = std::system(("bash -c '" + quoted + "'").c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_text(out_path);
  result.err = read_text(err_path);
  return result;
}

std::string data(const char* relative) { return "'" + test::data_path(relative) + "'"; }

int line_count(const std::string& text) {
  int lines = 0;
  for (const char c : text) lines += c == '\n';
  return lines;
}

// Exit 2, one line on stderr containing every one of `parts`.
void expect_refused(const std::string& arguments, const std::vector<std::string>& parts,
                    const std::string& shell_prefix = "") {
  SCOPED_TRACE(arguments);
  const RunResult r = run_cli(arguments, shell_prefix);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  for (const std::string& part : parts) {
    EXPECT_NE(r.err.find(part), std::string::npos) << "'" << part << "' in " << r.err;
  }
}

const std::string kMesh = data("blub/fish_low_resolution.obj");
const std::string kRig = data("rigs/blub_low_resolution.rig.json");

// ---------------------------------------------------------------------------------
// Numbers

TEST(CliNumbers, NegativeCountsAreErrorsNamingTheOptionAndTheValueAsTyped) {
  expect_refused("bench --mesh " + kMesh + " --frames -1", {"--frames '-1'", "[1, 1000000]"});
  expect_refused("bench --mesh " + kMesh + " --instances -1", {"--instances '-1'", "[1, "});
  const RunResult r = run_cli("bench --mesh " + kMesh + " --instances -1");
  EXPECT_EQ(r.err.find("18446744073709551615"), std::string::npos) << r.err;
  expect_refused("subdivide --in " + kMesh + " --out x.obj --levels -1", {"--levels '-1'"});
}

TEST(CliNumbers, HugeAndMalformedCountsAreRefusedWithTheLimit) {
  expect_refused("bench --mesh " + kMesh + " --instances 99999999999999999999999",
                 {"--instances '99999999999999999999999'", "above the limit 4294967295"});
  expect_refused("bench --mesh " + kMesh + " --frames 18446744073709551615",
                 {"--frames '18446744073709551615'", "above the limit 1000000"});
  expect_refused("bench --mesh " + kMesh + " --frames 1000001", {"above the limit 1000000"});
  for (const char* bad : {"0x10", "1e3", "1.5", "' 12'", "+3", "''", "12abc"}) {
    expect_refused("bench --mesh " + kMesh + " --frames " + bad, {"--frames '", "whole number"});
  }
  expect_refused("bench --mesh " + kMesh + " --instances 0", {"--instances '0'"});
  expect_refused("subdivide --in " + kMesh + " --out x.obj --levels 9",
                 {"--levels '9'", "above the limit 8"});
}

// --lanes and --stores go through bench's checks like every option: strict counts
// with their limit, then the lane counts the kernels have, then the kinds of store.
TEST(CliNumbers, BenchLanesAndStoresAreCheckedStrictly) {
  expect_refused("bench --mesh " + kMesh + " --lanes -1", {"--lanes '-1'", "[0, 32]"});
  expect_refused("bench --mesh " + kMesh + " --lanes 64",
                 {"--lanes '64'", "above the limit 32 (vertex slots per work-item)"});
  expect_refused("bench --mesh " + kMesh + " --lanes 8.0", {"--lanes '", "whole number"});
  expect_refused("bench --mesh " + kMesh + " --lanes 4", {"--lanes '4'", "1, 8, 16 or 32"});
  expect_refused("bench --mesh " + kMesh + " --stores fast",
                 {"--stores 'fast'", "auto, plain or streaming"});
}

TEST(CliNumbers, ParameterValuesBeyondFloatAreNamedAsTyped) {
  expect_refused("deform --in " + kMesh + " --out x.obj --rig " + kRig + " --set body_m=1e300",
                 {"--set body_m '1e300'", "float"});
  expect_refused("deform --in " + kMesh + " --out x.obj --m ' 0.5'",
                 {"--m ' 0.5'", "not a number"});
}

// ---------------------------------------------------------------------------------
// Paths that are not regular files

struct Special {
  std::string path;
  std::string kind;  // in the message
};

std::vector<Special> special_files() {
  const std::string fifo = test::temp_path("special.fifo");
  EXPECT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string folder = test::temp_path("folder.obj");
  fs::create_directory(folder);
  return {{fifo, "FIFO"}, {"/dev/zero", "character device"}, {folder, "directory"}};
}

TEST(CliPaths, InputsThatAreNotRegularFilesAreRefusedWithoutBlocking) {
  const std::string out = test::temp_path("never.obj");
  for (const Special& s : special_files()) {
    const std::string p = "'" + s.path + "'";
    expect_refused("deform --in " + p + " --out '" + out + "' --m 0.1", {"--in", s.path, s.kind});
    expect_refused("deform --in " + kMesh + " --out '" + out + "' --rig " + p,
                   {"--rig", s.path, s.kind});
    expect_refused("rig-info --in " + kMesh + " --rig " + p, {"--rig", s.path, s.kind});
    expect_refused("rig-info --in " + p + " --rig " + kRig, {"--in", s.path, s.kind});
    expect_refused("bench --mesh " + p + " --frames 1", {"--mesh", s.path, s.kind});
    expect_refused("bench --mesh " + kMesh + " --rig " + p, {"--rig", s.path, s.kind});
    expect_refused("check --in " + kMesh + " --rig " + p, {"--rig", s.path, s.kind});
    expect_refused("subdivide --in " + p + " --out '" + out + "'", {"--in", s.path, s.kind});
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliPaths, OutputsThatAreNotRegularFilesAreNeverReplaced) {
  for (const Special& s : special_files()) {
    if (s.path.rfind("/dev/", 0) == 0) continue;  // a device is never a test's output
    const std::string p = "'" + s.path + "'";
    expect_refused("rig-info --in " + kMesh + " --rig " + kRig + " --labels " + p,
                   {"--labels", s.path, s.kind});
    expect_refused("deform --in " + kMesh + " --out " + p + " --m 0.1", {"--out", s.path});
    expect_refused("subdivide --in " + kMesh + " --out " + p, {"--out", s.path});
    const fs::file_status status = fs::status(s.path);
    EXPECT_TRUE(fs::is_fifo(status) || fs::is_directory(status)) << s.path;
  }
}

TEST(CliPaths, OptionsAreCheckedBeforeAnyFileIsRead) {
  const std::string fifo = special_files().front().path;
  // A FIFO as the mesh would block a reader: the option errors come first.
  expect_refused("bench --mesh '" + fifo + "' --frames -1", {"--frames '-1'"});
  expect_refused("deform --in " + kMesh + " --out '" + test::temp_path("a.obj") + "' --rig '" +
                     fifo + "' --set body_m",
                 {"--rig", "FIFO"});
  expect_refused(
      "deform --in " + kMesh + " --out '" + test::temp_path("no/such/folder.obj") + "' --m 0.1",
      {"--out", "no/such", "No such file or directory"});
  expect_refused("deform --in " + kMesh + " --out '" + test::temp_path("x.xyz") + "' --m 0.1",
                 {"--out", ".xyz"});
}

// ---------------------------------------------------------------------------------
// --labels

std::vector<std::string> folder_entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  return names;
}

TEST(CliLabels, AFailedWriteLeavesTheExistingFileAndNoTemporaryFile) {
  const std::string labels = test::temp_path("labels.txt");
  { std::ofstream(labels) << "previous labels\n"; }
  // Files may grow to 4 KB: the labels (about 40 KB) cannot be written.
  const RunResult r =
      run_cli("rig-info --in " + kMesh + " --rig " + kRig + " --labels '" + labels + "'",
              "trap \"\" XFSZ; ulimit -f 4;");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--labels '" + labels + "'"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(labels), "previous labels\n");
  EXPECT_EQ(folder_entries(fs::path(labels).parent_path().string()),
            std::vector<std::string>{"labels.txt"});
}

TEST(CliLabels, AWrittenFileIsCompleteKeepsItsModeAndLeavesNothingElse) {
  const std::string labels = test::temp_path("labels.txt");
  { std::ofstream(labels) << "previous labels\n"; }
  fs::permissions(labels, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read,
                  fs::perm_options::replace);
  const RunResult r =
      run_cli("rig-info --in " + kMesh + " --rig " + kRig + " --labels '" + labels + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(labels);
  EXPECT_EQ(line_count(text), 946);  // a header and one line per vertex
  EXPECT_EQ(fs::status(labels).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(folder_entries(fs::path(labels).parent_path().string()),
            std::vector<std::string>{"labels.txt"});
}

}  // namespace
}  // namespace finflex

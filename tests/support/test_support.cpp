#include "support/test_support.hpp"

#include <atomic>
#include <cstdio>
#include <filesystem>

#include <cstdlib>

#include <unistd.h>

#include <gtest/gtest.h>

namespace finflex::test {

std::string data_path(const std::string& relative) {
  // FINFLEX_DATA_DIR in the environment overrides the source tree's data/ (for test
  // binaries run on another machine).
  const char* override_dir = std::getenv("FINFLEX_DATA_DIR");
  return std::string(override_dir && *override_dir ? override_dir : FINFLEX_DATA_DIR) + "/" +
         relative;
}

std::string temp_path(const std::string& file_name) {
  static std::atomic<int> counter{0};
  const std::string dir = std::string(FINFLEX_TEST_TMP_DIR) + "/" + std::to_string(getpid()) + "_" +
                          std::to_string(counter++);
  // A fresh, empty folder: an earlier run's process may have had the same id.
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir + "/" + file_name;
}

namespace {

std::atomic<bool> shared_context_made{false};

// The shared context's queues finish when the tests have run, before the program
// exits: PoCL compiles a kernel on its first launch in a thread of its own, and the
// LLVM state that compile makes is destroyed at exit before the shared context (a
// static made earlier), so its destructor would wait too late for work a test left
// queued.
class FinishSharedContext : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!shared_context_made) return;
    shared_context().queue().finish();
    shared_context().map_queue().finish();
  }
};

const ::testing::Environment* const finish_shared_context =
    ::testing::AddGlobalTestEnvironment(new FinishSharedContext);

}  // namespace

Context& shared_context() {
  static Context& context = []() -> Context& {
    setenv("POCL_CACHE_DIR", FINFLEX_TEST_POCL_CACHE, 0);
    static Context created;
    shared_context_made = true;
    return created;
  }();
  return context;
}

}  // namespace finflex::test

#include "support/test_support.hpp"

#include <atomic>
#include <cstdio>
#include <filesystem>

#include <cstdlib>

#include <unistd.h>

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

Context& shared_context() {
  static Context& context = []() -> Context& {
    setenv("POCL_CACHE_DIR", FINFLEX_TEST_POCL_CACHE, 0);
    static Context created;
    return created;
  }();
  return context;
}

}  // namespace finflex::test

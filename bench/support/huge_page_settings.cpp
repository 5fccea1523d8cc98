#include "huge_page_settings.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace finflex::bench {

std::string transparent_huge_pages() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(file, line)) return "unknown";
  // "always [madvise] never": the selected mode is in brackets.
  const std::size_t open = line.find('[');
  const std::size_t close = line.find(']');
  if (open == std::string::npos || close == std::string::npos || close <= open + 1) {
    return "unknown";
  }
  return line.substr(open + 1, close - open - 1);
}

std::string glibc_malloc_hugetlb() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string prefix = "glibc.malloc.hugetlb=";
  std::string value = "0";
  std::istringstream settings(tunables ? tunables : "");
  for (std::string setting; std::getline(settings, setting, ':');) {
    if (setting.compare(0, prefix.size(), prefix) == 0) value = setting.substr(prefix.size());
  }
  return value;
}

std::optional<std::uint64_t> process_huge_page_bytes() {
  std::ifstream file("/proc/self/smaps_rollup");
  const std::string key = "AnonHugePages:";
  for (std::string line; std::getline(file, line);) {
    if (line.compare(0, key.size(), key) != 0) continue;
    // "AnonHugePages:     253952 kB"
    std::istringstream fields(line.substr(key.size()));
    std::uint64_t kilobytes = 0;
    std::string unit;
    if (fields >> kilobytes >> unit && unit == "kB") return kilobytes * 1024;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace finflex::bench

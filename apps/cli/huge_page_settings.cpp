#include "huge_page_settings.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace finflex::cli {

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

}  // namespace finflex::cli

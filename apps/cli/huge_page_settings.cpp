#include "huge_page_settings.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace finflex::cli {

std::string transparent_huge_pages() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!file || !std::getline(file, line) || line.size() > 256) return "unknown";
  // "always [madvise] never": the selected mode is in brackets.
  const std::size_t open = line.find('[');
  const std::size_t close = line.find(']', open == std::string::npos ? 0 : open);
  if (open == std::string::npos || close == std::string::npos || close == open + 1) {
    return "unknown";
  }
  const std::string mode = line.substr(open + 1, close - open - 1);
  const bool word = std::all_of(mode.begin(), mode.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || c == '_' || c == '+';
  });
  return word ? mode : "unknown";
}

std::string glibc_malloc_hugetlb() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string prefix = "glibc.malloc.hugetlb=";
  std::string value = "0";
  if (tunables == nullptr) return value;
  const std::string settings = tunables;
  std::size_t start = 0;
  while (start <= settings.size()) {
    const std::size_t end = std::min(settings.find(':', start), settings.size());
    const std::string setting = settings.substr(start, end - start);
    if (setting.compare(0, prefix.size(), prefix) == 0) value = setting.substr(prefix.size());
    start = end + 1;
  }
  return value;
}

}  // namespace finflex::cli

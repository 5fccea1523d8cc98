#include "cli_paths.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "finflex/error.hpp"
#include "finflex/file_kind.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

void check_extension(const std::string& option, const std::string& path,
                     const std::vector<std::string>& extensions) {
  if (extensions.empty()) return;
  const std::string extension = lower(fs::path(path).extension().string());
  if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) return;
  std::string list;
  for (const std::string& e : extensions) list += (list.empty() ? "" : " ") + e;
  throw Error(ErrorCode::kFormat, option,
              option + " '" + path + "': unsupported extension '" +
                  fs::path(path).extension().string() + "' (expected one of: " + list + ")");
}

}  // namespace

const std::vector<std::string>& mesh_extensions() {
  static const std::vector<std::string> extensions = {".obj", ".ply",  ".off",
                                                      ".stl", ".gltf", ".glb"};
  return extensions;
}

void check_input_file(const std::string& option, const std::string& path,
                      const std::vector<std::string>& extensions) {
  const std::string quoted = option + " '" + path + "'";
  if (path.empty()) throw Error(ErrorCode::kInvalidArgument, option, option + " is empty");
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    const int error = errno;
    throw Error(ErrorCode::kIo, option, quoted + ": cannot read it (" + std::strerror(error) + ")");
  }
  const std::string kind = non_regular_kind(static_cast<unsigned>(status.st_mode));
  if (!kind.empty()) {
    throw Error(ErrorCode::kIo, option, quoted + ": is " + kind + ", not a regular file");
  }
  check_extension(option, path, extensions);
}

void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions) {
  const std::string quoted = option + " '" + path + "'";
  if (path.empty()) throw Error(ErrorCode::kInvalidArgument, option, option + " is empty");
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0) {
    const std::string kind = non_regular_kind(static_cast<unsigned>(status.st_mode));
    if (!kind.empty()) {
      throw Error(ErrorCode::kIo, option,
                  quoted + ": is " + kind + " (only a regular file is replaced)");
    }
  }
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  struct stat folder_status {};
  if (::stat(folder.c_str(), &folder_status) != 0) {
    const int error = errno;
    throw Error(ErrorCode::kIo, option,
                quoted + ": its folder '" + folder.string() + "' cannot be used (" +
                    std::strerror(error) + ")");
  }
  if (!S_ISDIR(folder_status.st_mode)) {
    throw Error(ErrorCode::kIo, option, quoted + ": '" + folder.string() + "' is not a folder");
  }
  check_extension(option, path, extensions);
}

}  // namespace finflex::cli

#include "staging_folder.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::cli {

namespace {

namespace fs = std::filesystem;

fs::path parent_of(const fs::path& path) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  fs::path parent =
      absolute.has_filename() ? absolute.parent_path() : absolute.parent_path().parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

std::string name_of(const fs::path& path) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  return absolute.has_filename() ? absolute.filename().string()
                                 : absolute.parent_path().filename().string();
}

}  // namespace

void check_output_folder(const std::string& out, const std::string& option) {
  std::error_code ec;
  const fs::path path(out);
  if (out.empty()) {
    throw Error(ErrorCode::kInvalidArgument, option, option + " is empty: name a folder");
  }
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) {
      throw Error(ErrorCode::kInvalidArgument, option, option + " '" + out + "' is not a folder");
    }
    if (access(out.c_str(), W_OK) != 0) {
      throw Error(ErrorCode::kIo, option, option + " '" + out + "': cannot write there");
    }
  }
  const fs::path parent = parent_of(path);
  if (!fs::is_directory(parent, ec)) {
    throw Error(
        ErrorCode::kIo, option,
        option + " '" + out + "': its parent folder '" + parent.string() + "' does not exist");
  }
  if (access(parent.c_str(), W_OK) != 0) {
    throw Error(
        ErrorCode::kIo, option,
        option + " '" + out + "': cannot write in its parent folder '" + parent.string() + "'");
  }
}

StagingFolder::StagingFolder(const std::string& target, const std::string& option)
    : target_(target), option_(option) {
  std::string pattern = (parent_of(target) / ("." + name_of(target) + ".partial-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) {
    throw Error(ErrorCode::kIo, option,
                option + " '" + target + "': cannot make a folder next to it (" +
                    std::strerror(errno) + ")");
  }
  path_ = buffer.data();
  // mkdtemp makes it 0700; the folder it becomes gets what mkdir would give it.
  const mode_t mask = umask(0);
  umask(mask);
  chmod(path_.c_str(), 0777 & ~mask);
}

StagingFolder::~StagingFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void StagingFolder::commit() {
  std::error_code ec;
  const fs::path target(target_);
  if (!fs::exists(target, ec)) {
    fs::rename(path_, target, ec);
    if (ec) {
      throw Error(ErrorCode::kIo, option_, option_ + " '" + target_ + "': " + ec.message());
    }
    committed_ = true;
    return;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(path_)) {
    const fs::path destination = target / entry.path().filename();
    fs::remove_all(destination, ec);
    fs::rename(entry.path(), destination, ec);
    if (ec) {
      throw Error(ErrorCode::kIo, option_,
                  option_ + " '" + destination.string() + "': " + ec.message());
    }
  }
  fs::remove(path_, ec);
  committed_ = true;
}

}  // namespace finflex::cli

#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

// A file created with mkstemp next to the target; removed on destruction unless
// renamed onto the target.
class TempFile {
 public:
  TempFile(const std::string& option, const fs::path& target) : option_(option) {
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::string pattern = (folder / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int fd = ::mkstemp(name.data());
    if (fd < 0) {
      fail(target.string(), "cannot create a temporary file in '" + folder.string() + "' (" +
                                std::strerror(errno) + ")");
    }
    path_ = name.data();
    struct stat existing {};
    mode_t mode = 0;
    if (::stat(target.c_str(), &existing) == 0 && S_ISREG(existing.st_mode)) {
      mode = existing.st_mode & 07777;
    } else {
      const mode_t mask = ::umask(0);
      ::umask(mask);
      mode = 0666 & ~mask;
    }
    ::fchmod(fd, mode);
    ::close(fd);
  }
  ~TempFile() {
    if (!path_.empty()) std::remove(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

  void sync(const std::string& target) const {
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
      const int error = errno;
      if (fd >= 0) ::close(fd);
      fail(target, std::string("cannot sync the written file (") + std::strerror(error) + ")");
    }
    ::close(fd);
  }

  void rename_onto(const std::string& target) {
    if (::rename(path_.c_str(), target.c_str()) != 0) {
      fail(target,
           std::string("cannot move the written file into place (") + std::strerror(errno) + ")");
    }
    path_.clear();
  }

  [[noreturn]] void fail(const std::string& target, const std::string& reason) const {
    throw Error(ErrorCode::kIo, option_, option_ + " '" + target + "': " + reason);
  }

 private:
  std::string option_;
  std::string path_;
};

}  // namespace

void write_file_atomically(const std::string& option, const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  TempFile temp(option, fs::path(path));
  {
    std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
    if (!out) temp.fail(path, "cannot open the temporary file '" + temp.path() + "'");
    write(out);
    out.flush();
    if (!out) temp.fail(path, "writing failed (disk full or file too large?)");
    out.close();
    if (out.fail()) temp.fail(path, "closing the written file failed (disk full?)");
  }
  temp.sync(path);
  temp.rename_onto(path);
}

}  // namespace finflex::cli

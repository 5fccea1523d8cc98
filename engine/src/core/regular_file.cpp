#include "core/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "finflex/error.hpp"

namespace finflex {

std::string non_regular_kind(unsigned st_mode) {
  switch (st_mode & S_IFMT) {
    case S_IFREG:
      return "";
    case S_IFDIR:
      return "a directory";
    case S_IFIFO:
      return "a FIFO (named pipe)";
    case S_IFCHR:
      return "a character device";
    case S_IFBLK:
      return "a block device";
    case S_IFSOCK:
      return "a socket";
    default:
      return "not a regular file";
  }
}

namespace detail {

FileDescriptor::~FileDescriptor() {
  if (fd_ >= 0) ::close(fd_);
}

std::string read_regular_file(const std::string& path, const std::string& field,
                              const std::string& what) {
  const std::string at = "'" + path + "': ";
  // Non-blocking: opening a FIFO for reading would otherwise wait for a writer.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (file.get() < 0) {
    const int error = errno;
    throw Error(ErrorCode::kIo, field,
                at + "cannot open " + what + " for reading (" + std::strerror(error) + ")");
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) {
    const int error = errno;
    throw Error(ErrorCode::kIo, field,
                at + "cannot stat " + what + " (" + std::strerror(error) + ")");
  }
  const std::string kind = non_regular_kind(static_cast<unsigned>(status.st_mode));
  if (!kind.empty()) {
    throw Error(ErrorCode::kIo, field, at + "is " + kind + ", not " + what + " (a regular file)");
  }
  std::string text;
  if (status.st_size > 0) text.reserve(static_cast<std::size_t>(status.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(file.get(), buffer, sizeof buffer);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      throw Error(ErrorCode::kIo, field,
                  at + "reading " + what + " failed (" + std::strerror(error) + ")");
    }
    text.append(buffer, static_cast<std::size_t>(got));
  }
  return text;
}

}  // namespace detail
}  // namespace finflex

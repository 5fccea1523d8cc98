// Reading an input file that must be a regular file: a FIFO, a device (/dev/zero), a
// socket or a directory is refused by its kind, without reading from it or waiting on
// it (it is opened non-blocking and checked on the open descriptor).
#pragma once

#include <string>

#include "finflex/file_kind.hpp"

namespace finflex::detail {

// All of the regular file at `path`. Throws kIo with `field`, the message starting
// with "'<path>': ", when it cannot be opened (with the system's reason), is not a
// regular file (naming what it is), or a read fails. `what` names the file in
// messages, e.g. "the rig file".
std::string read_regular_file(const std::string& path, const std::string& field,
                              const std::string& what);

// Closes a file descriptor when it goes out of scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor();
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace finflex::detail

#include "temp_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "render/error.hpp"

namespace finflex::render::detail {

namespace {

[[noreturn]] void io_error(const std::string& path, const std::string& what) {
  throw RenderError(ErrorCode::kIo, path,
                    "\"" + path + "\": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

TempFile::TempFile(const std::string& destination) : destination_(destination) {
  const std::size_t slash = destination.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : destination.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? destination : destination.substr(slash + 1);
  if (name.empty()) {
    errno = EISDIR;
    io_error(destination, "is not a file name");
  }
  std::string pattern = folder + "." + name + ".tmp-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  descriptor_ = mkostemp(buffer.data(), O_CLOEXEC);
  if (descriptor_ < 0) io_error(destination, "cannot create a file in its folder");
  path_ = buffer.data();
  fchmod(descriptor_, 0644);
}

TempFile::~TempFile() {
  if (descriptor_ >= 0) close(descriptor_);
  if (!committed_) std::remove(path_.c_str());
}

void TempFile::write(const void* data, std::size_t bytes) {
  const auto* next = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t written = ::write(descriptor_, next, bytes);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) io_error(destination_, "write failed");
    next += written;
    bytes -= static_cast<std::size_t>(written);
  }
}

void TempFile::commit() {
  const int descriptor = descriptor_;
  descriptor_ = -1;
  if (close(descriptor) != 0) io_error(destination_, "write failed");
  if (std::rename(path_.c_str(), destination_.c_str()) != 0) {
    io_error(destination_, "cannot be replaced");
  }
  committed_ = true;
}

void TempFile::discard() {
  if (descriptor_ >= 0) close(descriptor_);
  descriptor_ = -1;
  if (!committed_) std::remove(path_.c_str());
  committed_ = true;  // nothing left to remove
}

void write_file_atomically(const std::string& path, const void* data, std::size_t bytes) {
  TempFile file(path);
  file.write(data, bytes);
  file.commit();
}

}  // namespace finflex::render::detail

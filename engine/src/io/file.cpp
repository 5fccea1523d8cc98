// Reading input files: regular files only, whole, without ever blocking.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/regular_file.hpp"
#include "finflex/error.hpp"
#include "io/formats.hpp"

namespace finflex::io {
namespace {

[[noreturn]] void throw_io(const std::string& reason) {
  throw Error(ErrorCode::kIo, "path", reason);
}

// Why a file of this mode is not read, or "" for a regular file.
std::string refusal(mode_t mode) {
  const std::string kind = non_regular_kind(static_cast<unsigned>(mode));
  if (kind.empty()) return "";
  if (kind == "not a regular file") return "is not a regular file";
  return "is " + kind + ", not a regular file";
}

}  // namespace

void require_regular_file(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    if (errno == ENOENT) throw_io("file does not exist");
    throw_io(std::string("cannot access the file: ") + std::strerror(errno));
  }
  if (const std::string why = refusal(status.st_mode); !why.empty()) throw_io(why);
}

namespace {

std::string size_refusal(std::uint64_t size, std::uint64_t max_bytes, const char* limit) {
  return "has " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) +
         " " + limit;
}

// Reads the regular file `path`, at most `max_bytes` of it, into `bytes` (a string or
// a byte vector).
template <typename Bytes>
void read_into(const std::string& path, std::uint64_t max_bytes, const char* limit, Bytes& bytes) {
  // The type is checked before opening: opening a FIFO blocks until a writer comes,
  // and opening some devices has effects of its own.
  require_regular_file(path);
  // O_NONBLOCK: should the path have been replaced by a FIFO since, open returns at once.
  const detail::FileDescriptor file(
      ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (file.get() < 0) {
    throw_io(std::string("cannot open the file for reading: ") + std::strerror(errno));
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) {
    throw_io(std::string("cannot access the file: ") + std::strerror(errno));
  }
  if (const std::string why = refusal(status.st_mode); !why.empty()) throw_io(why);
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size > max_bytes) throw_io(size_refusal(size, max_bytes, limit));

  // The size is a hint: the file may change while it is read; what is read counts.
  bytes.assign(static_cast<std::size_t>(size), 0);
  std::size_t filled = 0;
  char chunk[65536];
  for (;;) {
    const bool into_bytes = filled < bytes.size();  // else: past the size, the file grew
    void* const target = into_bytes ? static_cast<void*>(bytes.data() + filled) : chunk;
    const std::size_t room = into_bytes ? bytes.size() - filled : sizeof chunk;
    const ssize_t n = ::read(file.get(), target, room);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_io(std::string("reading the file failed: ") + std::strerror(errno));
    }
    if (n == 0) break;
    if (!into_bytes) bytes.insert(bytes.end(), chunk, chunk + n);
    filled += static_cast<std::size_t>(n);
    if (filled > max_bytes) throw_io(size_refusal(filled, max_bytes, limit));
  }
  bytes.resize(filled);
}

}  // namespace

std::string read_regular_file(const std::string& path) {
  std::string bytes;
  read_into(path, std::numeric_limits<std::uint64_t>::max(), "", bytes);
  return bytes;
}

std::vector<unsigned char> read_regular_file_bytes(const std::string& path, std::uint64_t max_bytes,
                                                   const char* limit) {
  std::vector<unsigned char> bytes;
  read_into(path, max_bytes, limit, bytes);
  return bytes;
}

}  // namespace finflex::io

// load_mesh / save_mesh: format dispatch by extension, input checks, validation,
// error context and the atomic write (see finflex/mesh_io.hpp).
#include "finflex/mesh_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <random>
#include <string>
#include <string_view>
#include <system_error>

#include "finflex/error.hpp"
#include "io/formats.hpp"

namespace finflex {
namespace {

namespace fs = std::filesystem;
using io::MeshFormat;

struct FormatEntry {
  const char* extension;  // lower case, with the dot
  MeshFormat format;
};

constexpr FormatEntry kFormats[] = {
    {".obj", MeshFormat::kObj}, {".ply", MeshFormat::kPly},   {".off", MeshFormat::kOff},
    {".stl", MeshFormat::kStl}, {".gltf", MeshFormat::kGltf}, {".glb", MeshFormat::kGlb},
};

std::string quoted(const std::string& path) { return "'" + path + "'"; }

[[noreturn]] void throw_io(const std::string& path, const std::string& message) {
  throw Error(ErrorCode::kIo, "path", quoted(path) + ": " + message);
}

// Rethrows `error` with the path in front of its message; code and field are kept.
[[noreturn]] void rethrow_with_path(const Error& error, const std::string& path) {
  throw Error(error.code(), error.field(), quoted(path) + ": " + error.what());
}

std::string supported_extensions() {
  std::string list;
  for (const FormatEntry& entry : kFormats) {
    list += (list.empty() ? "" : " ") + std::string(entry.extension);
  }
  return list;
}

// The format named by the path's extension, compared case-insensitively; throws
// kFormat (the message does not name the path).
MeshFormat format_of_unquoted(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const FormatEntry& entry : kFormats) {
    if (extension == entry.extension) return entry.format;
  }
  const std::string found =
      extension.empty() ? "no extension" : "unsupported extension '" + extension + "'";
  throw Error(ErrorCode::kFormat, "path", found + " (supported: " + supported_extensions() + ")");
}

// format_of_unquoted, with the path in front of the message.
MeshFormat format_of(const std::string& path) {
  try {
    return format_of_unquoted(path);
  } catch (const Error& error) {
    rethrow_with_path(error, path);
  }
}

bool is_gltf(MeshFormat format) {
  return format == MeshFormat::kGltf || format == MeshFormat::kGlb;
}

}  // namespace

namespace io {

const char* format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj:
      return "OBJ";
    case MeshFormat::kPly:
      return "PLY";
    case MeshFormat::kOff:
      return "OFF";
    case MeshFormat::kStl:
      return "STL";
    case MeshFormat::kGltf:
      return "glTF";
    case MeshFormat::kGlb:
      return "GLB";
  }
  return "?";
}

Mesh read_mesh_bytes(std::string_view bytes, MeshFormat format, const std::string& base_dir) {
  if (bytes.empty()) throw Error(ErrorCode::kFormat, "path", "the file is empty");
  Mesh mesh;
  switch (format) {
    case MeshFormat::kObj:
      mesh = read_obj(bytes);
      break;
    case MeshFormat::kPly:
      mesh = read_ply(bytes);
      break;
    case MeshFormat::kOff:
      mesh = read_off(bytes);
      break;
    case MeshFormat::kStl:
      mesh = read_stl(bytes);
      break;
    case MeshFormat::kGltf:
    case MeshFormat::kGlb:
      mesh = read_gltf(bytes, base_dir);
      break;
  }
  if (!mesh.has_normals()) compute_vertex_normals(mesh);
  validate_mesh(mesh);
  return mesh;
}

}  // namespace io

namespace {

// ---------------------------------------------------------------------------------
// Atomic write

// A uniquely named, freshly created file next to `target`. Removed on destruction
// unless commit() has moved it onto the target.
class TempFile {
 public:
  explicit TempFile(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    std::random_device random;
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::string name = "." + target.filename().string() + ".tmp-" +
                               std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                               std::to_string(random());
      const fs::path candidate = folder / name;
      const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd >= 0) {
        ::close(fd);
        path_ = candidate;
        return;
      }
      if (errno != EEXIST) {
        throw_io(target.string(), "cannot create a temporary file in '" + folder.string() +
                                      "': " + std::strerror(errno));
      }
    }
    throw_io(target.string(), "cannot find a free temporary file name");
  }
  ~TempFile() {
    if (path_.empty()) return;
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const fs::path& path() const { return path_; }

  // Renames the file onto `target` (atomic on POSIX); afterwards nothing is removed.
  void commit(const fs::path& target) {
    std::error_code ec;
    fs::rename(path_, target, ec);
    if (ec) throw_io(target.string(), "cannot move the written file into place: " + ec.message());
    path_.clear();
  }

 private:
  fs::path path_;
};

// Flushes the file's data to the disk, so that the rename cannot expose an empty file
// after a crash.
void sync_to_disk(const fs::path& file, const std::string& target) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    throw_io(target, std::string("cannot reopen the written file: ") + std::strerror(errno));
  }
  const int result = ::fsync(fd);
  const int sync_errno = errno;
  ::close(fd);
  if (result != 0) {
    throw_io(target, std::string("cannot sync the file: ") + std::strerror(sync_errno));
  }
}

// Writes through `write` into a temporary file in the target's folder and renames
// it onto `path`. On any error the temporary file is removed and `path` is untouched.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  const fs::file_status folder_status = fs::status(folder, ec);
  if (!fs::exists(folder_status)) {
    throw_io(path, "the folder '" + folder.string() + "' does not exist");
  }
  if (!fs::is_directory(folder_status)) throw_io(path, "'" + folder.string() + "' is not a folder");
  if (fs::is_directory(target, ec)) throw_io(path, "is a directory");

  TempFile temp(target);
  {
    std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
    if (!out) throw_io(path, "cannot open the temporary file '" + temp.path().string() + "'");
    write(out);
    out.flush();
    if (!out) throw_io(path, "writing failed (disk full?)");
    out.close();
    if (out.fail()) throw_io(path, "closing the written file failed (disk full?)");
  }
  sync_to_disk(temp.path(), path);
  // A replaced file keeps its permission bits.
  const fs::file_status existing = fs::status(target, ec);
  if (!ec && fs::is_regular_file(existing)) {
    fs::permissions(temp.path(), existing.permissions(), fs::perm_options::replace, ec);
  }
  temp.commit(target);
}

}  // namespace

Mesh load_mesh(const std::string& path) {
  std::string bytes;
  MeshFormat format = MeshFormat::kObj;
  try {
    io::require_regular_file(path);  // first: a device or FIFO is refused whatever its name
    format = format_of_unquoted(path);
    bytes = io::read_regular_file(path);
  } catch (const Error& error) {
    rethrow_with_path(error, path);
  }
  const std::string base_dir = fs::path(path).parent_path().string();
  try {
    return io::read_mesh_bytes(bytes, format, base_dir);
  } catch (const Error& error) {
    rethrow_with_path(error, path);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::kFormat, "path", quoted(path) + ": out of memory while reading");
  } catch (const std::exception& error) {
    throw Error(ErrorCode::kFormat, "path", quoted(path) + ": cannot parse: " + error.what());
  }
}

void save_mesh(const std::string& path, const Mesh& mesh) {
  const MeshFormat format = format_of(path);
  try {
    validate_mesh(mesh);
  } catch (const Error& error) {
    rethrow_with_path(error, path);
  }
  Mesh with_normals;
  const Mesh* to_write = &mesh;
  if (!mesh.has_normals()) {
    with_normals = mesh;
    compute_vertex_normals(with_normals);
    to_write = &with_normals;
  }
  const auto write = [&](std::ostream& out) {
    try {
      if (is_gltf(format)) {
        io::write_gltf(out, format, *to_write);
      } else {
        io::write_openmesh(out, format, *to_write);
      }
    } catch (const Error& error) {
      rethrow_with_path(error, path);
    }
  };
  try {
    write_atomically(path, write);  // its own errors already name the path
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {
    throw_io(path, std::string("writing failed: ") + error.what());
  }
}

}  // namespace finflex

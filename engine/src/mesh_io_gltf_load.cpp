// glTF / GLB bytes to a tinygltf::Model, with the checks tinygltf leaves out.
//
// - GLB: the header's length and both chunk lengths are checked against the bytes
//   present (tinygltf lets a BIN chunk reach 8 bytes past the end of the data).
// - JSON: nesting deeper than kMaxJsonDepth is refused before parsing (tinygltf reads
//   "extras" recursively, one stack frame per level).
// - URIs: tinygltf reads buffers and images through file-system callbacks; ours read
//   regular files only (mesh_io_file.cpp), so a URI naming a folder, a FIFO or a
//   device fails at once with the reason instead of blocking or reading forever.
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "mesh_io_formats.hpp"
#include "mesh_io_gltf.hpp"

namespace finflex::io {
namespace {

[[noreturn]] void throw_format(const std::string& message) {
  throw Error(ErrorCode::kFormat, "path", message);
}

std::uint32_t load_u32(std::string_view bytes, std::size_t offset) {
  unsigned char b[4];
  std::memcpy(b, bytes.data() + offset, 4);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
         static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

// The JSON chunk of a GLB file, after checking the header and chunk lengths.
std::string_view glb_json(std::string_view bytes) {
  constexpr std::size_t kHeader = 12;
  constexpr std::size_t kChunkHeader = 8;
  if (bytes.size() < kHeader + kChunkHeader) {
    throw_format("GLB: " + std::to_string(bytes.size()) +
                 " bytes, less than the 20 of the header and the JSON chunk header");
  }
  const std::uint32_t version = load_u32(bytes, 4);
  if (version != 2) throw_format("GLB version " + std::to_string(version) + " (only 2 is read)");
  const std::uint32_t length = load_u32(bytes, 8);
  if (length != bytes.size()) {
    throw_format("GLB: the header gives the length " + std::to_string(length) +
                 ", but the file has " + std::to_string(bytes.size()) + " bytes");
  }
  const std::uint32_t json_length = load_u32(bytes, 12);
  if (load_u32(bytes, 16) != kChunkJson) throw_format("GLB: the first chunk is not JSON");
  const std::size_t after_json_header = kHeader + kChunkHeader;
  if (json_length > bytes.size() - after_json_header) {
    throw_format("GLB: the JSON chunk's length " + std::to_string(json_length) + " exceeds the " +
                 std::to_string(bytes.size() - after_json_header) + " bytes after its header");
  }
  const std::size_t bin = after_json_header + json_length;
  if (bin < bytes.size()) {
    if (bytes.size() - bin < kChunkHeader) {
      throw_format("GLB: " + std::to_string(bytes.size() - bin) +
                   " bytes after the JSON chunk, too few for a chunk header");
    }
    const std::uint32_t bin_length = load_u32(bytes, bin);
    if (load_u32(bytes, bin + 4) != kChunkBin) {
      throw_format("GLB: the chunk after the JSON chunk is not BIN");
    }
    if (bin_length > bytes.size() - bin - kChunkHeader) {
      throw_format("GLB: the BIN chunk's length " + std::to_string(bin_length) + " exceeds the " +
                   std::to_string(bytes.size() - bin - kChunkHeader) + " bytes after its header");
    }
  }
  return bytes.substr(after_json_header, json_length);
}

// Throws kFormat if arrays and objects in `json` nest deeper than kMaxJsonDepth,
// naming the line and byte where the limit is passed. Brackets inside strings do not
// count; unbalanced ones are left to the JSON parser.
void check_json_depth(std::string_view json) {
  std::size_t depth = 0;
  std::size_t line = 1;
  bool in_string = false;
  bool escaped = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        throw_format("JSON arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) +
                     " levels (line " + std::to_string(line) + ", byte " + std::to_string(i) +
                     " of the JSON text)");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// tinygltf's file-system callbacks.
bool file_exists(const std::string& path, void*) {
  struct stat status {};
  return ::stat(path.c_str(), &status) == 0;  // read_whole_file says what is wrong with it
}

std::string expand_file_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* error, const std::string& path,
                     void*) {
  try {
    *out = read_regular_file_bytes(path);
    return true;
  } catch (const Error& e) {
    if (error != nullptr) *error += e.what();
    return false;
  }
}

bool write_whole_file(std::string* error, const std::string&, const std::vector<unsigned char>&,
                      void*) {
  if (error != nullptr) *error += "writing is not done through the reader";
  return false;
}

// Image loader that keeps no pixels: textures play no part in a mesh, and a
// missing or undecodable image must not stop the load.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& c : text) {
    if (c == '\n') c = ';';
  }
  return text;
}

}  // namespace

LoadedGltf load_gltf_model(std::string_view bytes, const std::string& base_dir) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    throw_format("larger than 4 GiB, the most a glTF or GLB file may hold");
  }
  const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  check_json_depth(binary ? glb_json(bytes) : bytes);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_file_path, &read_whole_file,
                                              &write_whole_file, nullptr});
  LoadedGltf loaded;
  std::string error, warning;
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok = binary ? loader.LoadBinaryFromMemory(
                               &loaded.model, &error, &warning,
                               reinterpret_cast<const unsigned char*>(bytes.data()), size, base_dir)
                         : loader.LoadASCIIFromString(&loaded.model, &error, &warning, bytes.data(),
                                                      size, base_dir);
  if (!ok) {
    // A missing or unreadable external buffer is an I/O problem, the rest is content.
    const bool io = error.find("File not found") != std::string::npos ||
                    error.find("File read error") != std::string::npos ||
                    error.find("Failed to load external") != std::string::npos;
    throw Error(io ? ErrorCode::kIo : ErrorCode::kFormat, "path",
                "not a readable glTF file: " + one_line(error.empty() ? "unknown error" : error));
  }
  loaded.input_bytes = bytes.size();
  for (const tinygltf::Buffer& buffer : loaded.model.buffers) {
    loaded.input_bytes += buffer.data.size();
  }
  return loaded;
}

}  // namespace finflex::io

// glTF / GLB bytes to a tinygltf::Model, with the checks tinygltf leaves out.
//
// - GLB: the header's length and both chunk lengths are checked against the bytes
//   present (tinygltf lets a BIN chunk reach 8 bytes past the end of the data).
// - JSON: nesting deeper than kMaxJsonDepth is refused before parsing (tinygltf reads
//   "extras" recursively, one stack frame per level).
// - URIs: tinygltf reads buffers and images through file-system callbacks; ours read
//   regular files only (mesh_io_file.cpp), so a URI naming a folder, a FIFO or a
//   device fails at once with the reason instead of blocking or reading forever. They
//   read at most as many bytes in all as the "buffers" entries declare (byteLength):
//   tinygltf reads external buffers first and needs each to have exactly its declared
//   size, so images, which are not decoded, get only what data URI and GLB buffers
//   leave, and a URI naming a huge file is refused before it is read.
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "finflex/error.hpp"
#include "io/formats.hpp"
#include "io/gltf.hpp"

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

// The sum of the byteLength members of the top-level "buffers" entries, found by the
// JSON parser's event interface without building a document. (Invalid JSON gives what
// was found before the error; tinygltf then reports the error.)
class BufferLengths {
 public:
  std::uint64_t total() const { return total_; }

  bool null() { return value(std::nullopt); }
  bool boolean(bool) { return value(std::nullopt); }
  bool number_integer(std::int64_t v) {
    return value(v >= 0 ? std::optional<std::uint64_t>(static_cast<std::uint64_t>(v))
                        : std::nullopt);
  }
  bool number_unsigned(std::uint64_t v) { return value(v); }
  bool number_float(double v, const std::string&) {
    constexpr double kMax = 1.8e19;  // above: the most a sum can hold
    if (!(v >= 0.0)) return value(std::nullopt);
    return value(v < kMax ? static_cast<std::uint64_t>(v) : kNoLimit);
  }
  bool string(std::string&) { return value(std::nullopt); }
  bool binary(nlohmann::json::binary_t&) { return value(std::nullopt); }
  bool start_object(std::size_t) { return open(); }
  bool start_array(std::size_t) {
    if (depth_ == 1 && buffers_key_) in_buffers_ = true;
    return open();
  }
  bool end_object() { return close(); }
  bool end_array() {
    close();
    if (depth_ == 1) in_buffers_ = false;
    return true;
  }
  bool key(std::string& name) {
    if (depth_ == 1) buffers_key_ = name == "buffers";
    if (depth_ == 3) length_key_ = in_buffers_ && name == "byteLength";
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) {
    return false;
  }

 private:
  static constexpr std::uint64_t kNoLimit = std::numeric_limits<std::uint64_t>::max();

  bool value(std::optional<std::uint64_t> number) {
    if (length_key_ && number) total_ = *number > kNoLimit - total_ ? kNoLimit : total_ + *number;
    buffers_key_ = false;
    length_key_ = false;
    return true;
  }
  bool open() {
    buffers_key_ = false;
    length_key_ = false;
    ++depth_;
    return true;
  }
  bool close() {
    --depth_;
    return true;
  }

  std::uint64_t total_ = 0;
  std::size_t depth_ = 0;     // open objects and arrays; the root object is 1
  bool buffers_key_ = false;  // the last key at depth 1 was "buffers"
  bool in_buffers_ = false;   // inside the top-level "buffers" array
  bool length_key_ = false;   // the last key of a buffer object was "byteLength"
};

std::uint64_t declared_buffer_bytes(std::string_view json) {
  BufferLengths lengths;
  nlohmann::json::sax_parse(json.begin(), json.end(), &lengths);
  return lengths.total();
}

// tinygltf's file-system callbacks; user data: the bytes they may still read.
bool file_exists(const std::string& path, void*) {
  struct stat status {};
  return ::stat(path.c_str(), &status) == 0;  // read_whole_file says what is wrong with it
}

std::string expand_file_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* error, const std::string& path,
                     void* user_data) {
  std::uint64_t& budget = *static_cast<std::uint64_t*>(user_data);
  try {
    *out = read_regular_file_bytes(path, budget,
                                   "bytes that the glTF buffers' byteLength leave to read");
    budget -= out->size();
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

// tinygltf's error text made fit for one message line: lines joined with "; ", bytes
// that are not printable ASCII as '?' (the text quotes URIs and JSON from the file),
// words longer than 60 characters (a data URI) cut, at most 1000 characters.
std::string one_line(std::string_view text) {
  constexpr std::size_t kMaxWord = 60;
  constexpr std::size_t kMaxText = 1000;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  std::string out;
  std::size_t word = 0;  // length of the current word so far
  for (const char raw : text) {
    if (out.size() >= kMaxText) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(raw);
    if (c == '\n') {
      out += "; ";
      word = 0;
      continue;
    }
    word = c == ' ' ? 0 : word + 1;
    if (word > kMaxWord) {
      if (word == kMaxWord + 1) out += "...";
      continue;
    }
    out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  return out;
}

}  // namespace

LoadedGltf load_gltf_model(std::string_view bytes, const std::string& base_dir) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    throw_format("larger than 4 GiB, the most a glTF or GLB file may hold");
  }
  const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  const std::string_view json = binary ? glb_json(bytes) : bytes;
  check_json_depth(json);
  std::uint64_t read_budget = declared_buffer_bytes(json);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_file_path, &read_whole_file,
                                              &write_whole_file, &read_budget});
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

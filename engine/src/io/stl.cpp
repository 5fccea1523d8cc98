// Strict STL reader, binary and ASCII.
//
// Binary: an 80-byte header, a little-endian u32 triangle count, then 50 bytes per
// triangle (facet normal, three corners, attribute count; all floats little endian).
// A file is binary when its size is exactly 84 + 50 * count; otherwise it must be
// ASCII, starting with "solid":
//   solid [name]
//     facet normal nx ny nz
//       outer loop
//         vertex x y z      (three times)
//       endloop
//     endfacet
//   endsolid [name]
// Keywords are case-insensitive; several solids may follow each other. Facet normals
// are checked to be numbers and then dropped (normals are computed from the
// triangles). Corner coordinates must be finite. STL has no shared vertices: one
// vertex is made per distinct position (+0 and -0 are the same), numbered in order of
// first use, and every facet becomes one triangle, degenerate ones included. Errors
// name the line (ASCII) or the triangle (binary).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "finflex/error.hpp"
#include "io/builder.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"

namespace finflex::io {
namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kTriangleBytes = 50;

// Vertices keyed by their position's bits (with -0 as +0): equal positions share one.
class VertexMerger {
 public:
  std::uint32_t vertex_of(const glm::vec3& p) {
    const Key key{bits(p.x), bits(p.y), bits(p.z)};
    const auto [it, inserted] = index_.try_emplace(key, 0u);
    if (inserted) it->second = builder_.add_vertex(p);
    return it->second;
  }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    triangle_.assign({a, b, c});
    builder_.add_polygon(triangle_);
  }
  Mesh finish() { return builder_.finish(); }

 private:
  struct Key {
    std::uint32_t x, y, z;
    bool operator==(const Key& other) const { return x == other.x && y == other.y && z == other.z; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
      h ^= (h >> 29) + k.y * 0xBF58476D1CE4E5B9ull;
      h ^= (h >> 31) + k.z * 0x94D049BB133111EBull;
      return static_cast<std::size_t>(h ^ (h >> 32));
    }
  };
  static std::uint32_t bits(float value) {
    const float canonical = value == 0.0f ? 0.0f : value;  // -0 -> +0
    std::uint32_t b = 0;
    std::memcpy(&b, &canonical, sizeof b);
    return b;
  }

  MeshBuilder builder_;
  std::unordered_map<Key, std::uint32_t, KeyHash> index_;
  std::vector<std::uint32_t> triangle_;
};

std::uint32_t load_u32(const char* p) {
  unsigned char b[4];
  std::memcpy(b, p, 4);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
         static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

float load_f32(const char* p) {
  const std::uint32_t bits = load_u32(p);
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// The triangle count in a binary header, and whether the file's size matches it.
bool is_binary(std::string_view bytes, std::uint32_t& count) {
  count = 0;
  if (bytes.size() < kHeaderBytes) return false;
  count = load_u32(bytes.data() + 80);
  return bytes.size() - kHeaderBytes == std::uint64_t{count} * kTriangleBytes;
}

Mesh read_binary(std::string_view bytes, std::uint32_t count) {
  VertexMerger merger;
  static const char* const kAxes[] = {"x", "y", "z"};
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* facet = bytes.data() + kHeaderBytes + std::size_t{t} * kTriangleBytes;
    std::uint32_t corners[3];
    for (int k = 0; k < 3; ++k) {
      glm::vec3 p;
      for (int c = 0; c < 3; ++c) {
        p[c] = load_f32(facet + 12 + 12 * k + 4 * c);
        if (!std::isfinite(p[c])) {
          const std::string field = "triangles[" + std::to_string(t) + "]";
          throw_at(ErrorCode::kInvalidMesh, field,
                   "corner " + std::to_string(k + 1) + " " + kAxes[c] + " is " +
                       (std::isnan(p[c]) ? "NaN"
                        : p[c] > 0       ? "+inf"
                                         : "-inf"));
        }
      }
      corners[k] = merger.vertex_of(p);
    }
    merger.add_triangle(corners[0], corners[1], corners[2]);
  }
  return merger.finish();
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

// The ASCII grammar, one line per statement (as every STL writer puts it).
class AsciiStlReader {
 public:
  explicit AsciiStlReader(std::string_view text) : lines_(text) {}
  Mesh read();

 private:
  // The next non-blank line's words into words_; false at the end of the text.
  bool next_words();
  // Reads the next line and checks it is `keyword` followed by `numbers` numbers (or,
  // with numbers < 0, by anything: a solid's name).
  void expect(std::string_view keyword, std::string_view second, int numbers);
  std::string where() const { return line_field(line_.number); }
  void read_facet();

  LineReader lines_;
  TextLine line_;
  std::vector<std::string_view> words_;
  VertexMerger merger_;
};

bool AsciiStlReader::next_words() {
  while (lines_.next(line_)) {
    split_words(line_.text, words_);
    if (!words_.empty()) return true;
  }
  return false;
}

void AsciiStlReader::expect(std::string_view keyword, std::string_view second, int numbers) {
  const std::string wanted =
      std::string(keyword) + (second.empty() ? "" : " " + std::string(second));
  if (!next_words()) {
    throw_at(ErrorCode::kFormat, where(), "the file ends where '" + wanted + "' should follow");
  }
  const std::size_t first_number = second.empty() ? 1 : 2;
  const bool keywords_match =
      equals_ignoring_case(words_[0], keyword) &&
      (second.empty() || (words_.size() > 1 && equals_ignoring_case(words_[1], second)));
  if (!keywords_match) {
    throw_at(ErrorCode::kFormat, where(), "expected '" + wanted + "', found " + shown(line_.text));
  }
  if (numbers >= 0 && words_.size() != first_number + static_cast<std::size_t>(numbers)) {
    throw_at(ErrorCode::kFormat, where(),
             "'" + wanted + "' needs " + std::to_string(numbers) + " numbers, found " +
                 std::to_string(words_.size() - first_number));
  }
}

void AsciiStlReader::read_facet() {
  static const char* const kNormal[] = {"facet normal x", "facet normal y", "facet normal z"};
  static const char* const kVertex[] = {"vertex x", "vertex y", "vertex z"};
  // "facet normal" is already in words_.
  if (words_.size() != 5) {
    throw_at(ErrorCode::kFormat, where(),
             "'facet normal' needs 3 numbers, found " + std::to_string(words_.size() - 2));
  }
  for (std::size_t c = 0; c < 3; ++c) {
    float ignored = 0.0f;
    const NumberError error = parse_float(words_[2 + c], ignored);
    // Writers put NaN or zero normals on degenerate facets; only unreadable ones count.
    if (error == NumberError::kUnreadable)
      throw_float_error(error, words_[2 + c], where(), kNormal[c]);
  }
  expect("outer", "loop", 0);
  std::uint32_t corners[3];
  for (int k = 0; k < 3; ++k) {
    expect("vertex", "", 3);
    glm::vec3 p;
    for (int c = 0; c < 3; ++c) {
      p[c] = read_float(words_[1 + static_cast<std::size_t>(c)], where(), kVertex[c]);
    }
    corners[k] = merger_.vertex_of(p);
  }
  expect("endloop", "", 0);
  expect("endfacet", "", 0);
  merger_.add_triangle(corners[0], corners[1], corners[2]);
}

Mesh AsciiStlReader::read() {
  bool any_solid = false;
  while (next_words()) {
    if (!equals_ignoring_case(words_[0], "solid")) {
      throw_at(ErrorCode::kFormat, where(),
               any_solid ? "expected 'solid' or the end of the file, found " + shown(line_.text)
                         : "expected 'solid', found " + shown(line_.text));
    }
    any_solid = true;
    const std::size_t solid_line = line_.number;
    for (;;) {
      if (!next_words()) {
        throw_at(
            ErrorCode::kFormat, where(),
            "the file ends inside the solid of " + line_field(solid_line) + " (no 'endsolid')");
      }
      if (equals_ignoring_case(words_[0], "endsolid")) break;
      if (!equals_ignoring_case(words_[0], "facet") || words_.size() < 2 ||
          !equals_ignoring_case(words_[1], "normal")) {
        throw_at(ErrorCode::kFormat, where(),
                 "expected 'facet normal' or 'endsolid', found " + shown(line_.text));
      }
      read_facet();
    }
  }
  return merger_.finish();
}

bool starts_with_solid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (is_blank(bytes[i]) || bytes[i] == '\n')) ++i;
  return equals_ignoring_case(bytes.substr(i, 5), "solid");
}

}  // namespace

Mesh read_stl(std::string_view bytes) {
  std::uint32_t count = 0;
  if (is_binary(bytes, count)) {
    if (count == 0) {
      throw Error(ErrorCode::kFormat, "positions", "positions: the binary STL has 0 triangles");
    }
    return read_binary(bytes, count);
  }
  const std::string as_binary =
      "as binary STL its header declares " + std::to_string(count) +
      " triangles, which take 84 + 50 * " + std::to_string(count) + " = " +
      std::to_string(kHeaderBytes + std::uint64_t{count} * kTriangleBytes) +
      " bytes, but the file has " + std::to_string(bytes.size());
  if (starts_with_solid(bytes)) {
    Mesh mesh;
    try {
      mesh = AsciiStlReader(bytes).read();
    } catch (const Error& error) {
      // Some binary files start their header with "solid": say what binary would need.
      const bool has_nul = bytes.substr(0, 1024).find('\0') != std::string_view::npos;
      if (!has_nul || bytes.size() < kHeaderBytes || error.code() != ErrorCode::kFormat) throw;
      throw Error(error.code(), error.field(),
                  std::string(error.what()) + " (and " + as_binary + ")");
    }
    if (mesh.positions.empty()) {
      throw Error(ErrorCode::kFormat, "positions", "positions: the ASCII STL has no facets");
    }
    return mesh;
  }
  if (bytes.size() < kHeaderBytes) {
    throw Error(ErrorCode::kFormat, "path",
                "neither ASCII STL (it does not start with 'solid') nor binary STL (" +
                    std::to_string(bytes.size()) + " bytes, less than the 84-byte header)");
  }
  throw Error(ErrorCode::kFormat, "path",
              "not ASCII STL (it does not start with 'solid'), and " + as_binary);
}

}  // namespace finflex::io

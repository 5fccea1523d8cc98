// Strict OFF reader (ASCII; Geomview's layout as OpenMesh writes it).
//
//   [ST][C][N]OFF            header keyword: texcoords, colors, normals per vertex
//   nV nF [nE]               counts (on the keyword's line or the next); nE is ignored
//   x y z [nx ny nz] [r g b [a]] [s t]      nV vertex lines
//   n i1 ... in [0 to 4 color values]       nF face lines, indices from 0
// Blank lines and comments ('#' starting a word) may come anywhere. The keywords 4OFF
// and nOFF with a dimension other than 3, and binary OFF, are not supported. Normals
// and texcoords are kept, colors are checked and dropped. The counts are checked
// against the bytes after them before anything is allocated; every number must be all
// of its token and finite; a face needs 3 distinct existing vertices; nothing may
// follow the last face. Errors name the line.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "finflex/error.hpp"
#include "io/builder.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"

namespace finflex::io {
namespace {

// What the header keyword says each vertex line holds.
struct OffLayout {
  bool texcoords = false;  // "ST"
  bool colors = false;     // "C"
  bool normals = false;    // "N"
};

// The smallest vertex line ("0 0 0\n") and face line ("3 0 1 2\n"), in bytes.
constexpr std::uint64_t kMinVertexBytes = 6;
constexpr std::uint64_t kMinFaceBytes = 8;

class OffReader {
 public:
  explicit OffReader(std::string_view text) : lines_(text) {}
  Mesh read();

 private:
  // The next line with words (blank and comment lines skipped) into words_; false at
  // the end of the text.
  bool next_words();
  void read_header();
  void read_counts(std::size_t first_word);
  void read_vertex();
  void read_face(std::uint64_t face);
  std::string where() const { return line_field(line_.number); }

  LineReader lines_;
  TextLine line_;
  std::vector<std::string_view> words_;
  OffLayout layout_;
  std::uint64_t vertex_count_ = 0;
  std::uint64_t face_count_ = 0;
  MeshBuilder builder_;
  std::vector<std::uint32_t> polygon_;
};

bool OffReader::next_words() {
  while (lines_.next(line_)) {
    split_words(strip_comment(line_.text), words_);
    if (!words_.empty()) return true;
  }
  return false;
}

void OffReader::read_header() {
  if (!next_words()) throw Error(ErrorCode::kFormat, "path", "no OFF header keyword");
  std::string_view keyword = words_[0];
  const auto take = [&keyword](std::string_view prefix) {
    if (keyword.substr(0, prefix.size()) != prefix) return false;
    keyword.remove_prefix(prefix.size());
    return true;
  };
  layout_.texcoords = take("ST");
  layout_.colors = take("C");
  layout_.normals = take("N");
  if (keyword == "4OFF" || keyword == "nOFF" || keyword == "4nOFF") {
    const bool three = keyword == "nOFF" && words_.size() > 1 && words_[1] == "3";
    if (!three) {
      throw_at(ErrorCode::kFormat, where(),
               "OFF keyword " + shown(words_[0]) + ": only 3D vertices are supported");
    }
    words_.erase(words_.begin() + 1);  // the dimension
    keyword = "OFF";
  }
  if (keyword != "OFF") {
    throw_at(ErrorCode::kFormat, where(),
             "no OFF header: " + shown(words_[0]) + " is not [ST][C][N]OFF");
  }
  if (words_.size() > 1 && words_[1] == "BINARY") {
    throw_at(ErrorCode::kFormat, where(), "binary OFF is not supported, only ASCII");
  }
  if (words_.size() > 1) {
    read_counts(1);
  } else {
    if (!next_words()) {
      throw_at(ErrorCode::kFormat, where(), "the file ends before the counts line (nV nF nE)");
    }
    read_counts(0);
  }
}

void OffReader::read_counts(std::size_t first_word) {
  const std::size_t n = words_.size() - first_word;
  if (n != 2 && n != 3) {
    throw_at(ErrorCode::kFormat, where(),
             "the counts line needs 'nV nF nE' (vertices, faces, edges); found " +
                 std::to_string(n) + " words");
  }
  static const char* const kNames[] = {"vertex count", "face count", "edge count"};
  std::int64_t counts[3] = {0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    counts[k] = read_int(words_[first_word + k], where(), kNames[k]);
    if (counts[k] < 0) {
      throw_at(ErrorCode::kFormat, where(),
               std::string(kNames[k]) + " " + std::to_string(counts[k]) + " is negative");
    }
  }
  vertex_count_ = static_cast<std::uint64_t>(counts[0]);
  face_count_ = static_cast<std::uint64_t>(counts[1]);
  // Every vertex and face takes a line of some bytes: counts the rest of the file
  // cannot hold are refused before anything is allocated.
  // (The last line may lack its "\n": one byte more.)
  const std::uint64_t bytes = lines_.remaining();
  const std::uint64_t room = bytes + 1;
  const bool vertices_fit = vertex_count_ <= room / kMinVertexBytes;
  const bool faces_fit =
      vertices_fit && face_count_ <= (room - vertex_count_ * kMinVertexBytes) / kMinFaceBytes;
  if (!vertices_fit || !faces_fit) {
    throw_at(ErrorCode::kFormat, where(),
             "the header declares " + std::to_string(vertex_count_) + " vertices and " +
                 std::to_string(face_count_) + " faces, but the " + std::to_string(bytes) +
                 " bytes after it cannot hold them (at least " + std::to_string(kMinVertexBytes) +
                 " bytes per vertex and " + std::to_string(kMinFaceBytes) +
                 " per face; truncated file or wrong count)");
  }
}

void OffReader::read_vertex() {
  const std::size_t base = 3 + (layout_.normals ? 3 : 0) + (layout_.texcoords ? 2 : 0);
  const std::size_t n = words_.size();
  const bool fits = layout_.colors ? n == base + 3 || n == base + 4 : n == base;
  if (!fits) {
    throw_at(ErrorCode::kFormat, where(),
             "vertex line has " + std::to_string(n) + " numbers, the header keyword asks for " +
                 std::to_string(base) + (layout_.colors ? " plus 3 or 4 color values" : ""));
  }
  // The line's values in order, each with its name.
  std::vector<std::pair<const char*, float*>> fields;
  glm::vec3 position(0.0f), normal(0.0f);
  glm::vec2 texcoord(0.0f);
  float color = 0.0f;  // checked, not kept
  fields.insert(fields.end(), {{"x", &position.x}, {"y", &position.y}, {"z", &position.z}});
  if (layout_.normals) {
    fields.insert(fields.end(), {{"nx", &normal.x}, {"ny", &normal.y}, {"nz", &normal.z}});
  }
  if (layout_.colors) {
    fields.insert(fields.end(), {{"r", &color}, {"g", &color}, {"b", &color}});
    if (n == base + 4) fields.push_back({"a", &color});
  }
  if (layout_.texcoords) fields.insert(fields.end(), {{"s", &texcoord.x}, {"t", &texcoord.y}});
  for (std::size_t k = 0; k < n; ++k) {
    *fields[k].second = read_float(words_[k], where(), std::string("vertex ") + fields[k].first);
  }
  const std::uint32_t v = builder_.add_vertex(position);
  if (layout_.normals) builder_.add_normal(v, normal);
  if (layout_.texcoords) builder_.add_texcoord(v, texcoord);
}

void OffReader::read_face(std::uint64_t face) {
  const std::int64_t n = read_int(words_[0], where(), "face corner count");
  const std::size_t available = words_.size() - 1;
  if (n < 3 || static_cast<std::uint64_t>(n) > available) {
    throw_at(ErrorCode::kFormat, where(),
             "face " + std::to_string(face) + " has corner count " + std::to_string(n) +
                 (n < 3 ? ", at least 3 needed"
                        : ", but only " + std::to_string(available) + " numbers follow"));
  }
  const std::size_t corners = static_cast<std::size_t>(n);
  if (available - corners > 4) {
    throw_at(ErrorCode::kFormat, where(),
             "face " + std::to_string(face) + " has " + std::to_string(available - corners) +
                 " numbers after its " + std::to_string(corners) +
                 " corners (at most 4 color values may follow)");
  }
  polygon_.clear();
  for (std::size_t k = 0; k < corners; ++k) {
    const std::string what = "face " + std::to_string(face) + " corner " + std::to_string(k + 1);
    const std::int64_t index = read_int(words_[k + 1], where(), what);
    if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count_) {
      throw_at(ErrorCode::kInvalidMesh, where(),
               what + ": vertex index " + std::to_string(index) + " is out of range (" +
                   std::to_string(vertex_count_) + " vertices)");
    }
    polygon_.push_back(static_cast<std::uint32_t>(index));
  }
  for (std::size_t k = 1 + corners; k < words_.size(); ++k) {
    read_float(words_[k], where(), "face " + std::to_string(face) + " color value");
  }
  if (const auto repeat = find_repeated_corner(polygon_)) {
    throw_at(ErrorCode::kInvalidMesh, where(),
             "face " + std::to_string(face) + " uses vertex " +
                 std::to_string(polygon_[repeat->first]) + " at corners " +
                 std::to_string(repeat->first + 1) + " and " + std::to_string(repeat->second + 1) +
                 " (a polygon's corners must be distinct)");
  }
  builder_.add_polygon(polygon_);
}

Mesh OffReader::read() {
  read_header();
  if (vertex_count_ == 0) {
    throw Error(ErrorCode::kFormat, "positions", "positions: the OFF header declares 0 vertices");
  }
  for (std::uint64_t v = 0; v < vertex_count_; ++v) {
    if (!next_words()) {
      throw_at(ErrorCode::kFormat, where(),
               "the file ends after " + std::to_string(v) + " of the " +
                   std::to_string(vertex_count_) + " vertices the header declares");
    }
    read_vertex();
  }
  for (std::uint64_t f = 0; f < face_count_; ++f) {
    if (!next_words()) {
      throw_at(ErrorCode::kFormat, where(),
               "the file ends after " + std::to_string(f) + " of the " +
                   std::to_string(face_count_) + " faces the header declares");
    }
    read_face(f);
  }
  if (next_words()) {
    throw_at(ErrorCode::kFormat, where(),
             "content after the last of the " + std::to_string(face_count_) +
                 " faces the header declares: " + shown(line_.text));
  }
  return builder_.finish();
}

}  // namespace

Mesh read_off(std::string_view text) { return OffReader(text).read(); }

}  // namespace finflex::io

// Strict Wavefront OBJ reader.
//
// Statements read (one per line; a '#' that starts a word begins a comment):
//   v x y z [w | r g b | w r g b]   a vertex (w and colors are checked, not kept)
//   vt u [v [w]]                    a texcoord (v defaults to 0; w is not kept)
//   vn x y z                        a normal
//   f c1 c2 c3 ...                  a polygon; corners v, v/vt, v//vn or v/vt/vn;
//                                   indices from 1, negative ones count back from the
//                                   last statement of their kind before the face
//   g name, o name                  groups (FaceGroup): "g" lines, else "o" lines
// Statements allowed by the format and ignored: s, usemtl, mtllib, l, p, vp and the
// display and render attributes (lod, mg, maplib, usemap, bevel, c_interp, d_interp,
// shadow_obj, trace_obj, ctech, stech). Everything else is an error, among them
// free-form geometry (curv, surf, ...) and line continuations ('\' at the end).
// Every number must be all of its token and finite; every index must exist (positive
// indices may refer to statements later in the file); a polygon needs 3 distinct
// vertices. Errors name the line.
#include <algorithm>
#include <array>
#include <cstdint>
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

constexpr std::array<std::string_view, 17> kIgnored = {
    "s",        "usemtl",     "mtllib",    "l",      "p",     "vp",
    "lod",      "mg",         "maplib",    "usemap", "bevel", "c_interp",
    "d_interp", "shadow_obj", "trace_obj", "ctech",  "stech"};
constexpr std::array<std::string_view, 14> kFreeForm = {"cstype", "deg",  "bmat", "step", "curv",
                                                        "curv2",  "surf", "parm", "trim", "hole",
                                                        "scrv",   "sp",   "end",  "con"};

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& words, std::string_view word) {
  return std::find(words.begin(), words.end(), word) != words.end();
}

// A face corner: 0-based indices into the v, vt and vn statements; -1 where the
// corner gives none. Negative file indices are resolved when read; positive ones
// are checked once the whole file is read.
struct Corner {
  std::int64_t v = -1;
  std::int64_t vt = -1;
  std::int64_t vn = -1;
};

struct Face {
  std::size_t line = 0;
  std::size_t first_corner = 0;  // into ObjReader::corners_
  std::size_t corner_count = 0;
  std::size_t g = 0;  // 1 + index into g_names_; 0: no group
  std::size_t o = 0;  // 1 + index into o_names_; 0: no object
};

// Group or object names, each with a number from 1 (0: no name).
class NameTable {
 public:
  // The number of `name`, added if new; 0 for an empty name.
  std::size_t intern(std::string_view name) {
    if (name.empty()) return 0;
    const auto [it, added] = numbers_.try_emplace(std::string(name), names_.size() + 1);
    if (added) names_.push_back(&it->first);
    return it->second;
  }
  bool empty() const { return names_.empty(); }
  const std::string& name(std::size_t number) const { return *names_[number - 1]; }

 private:
  std::unordered_map<std::string, std::size_t> numbers_;
  std::vector<const std::string*> names_;  // keys of numbers_, which stay in place
};

class ObjReader {
 public:
  void read(std::string_view text);
  Mesh build() const;

 private:
  void read_line(std::string_view content);
  void read_vertex();
  void read_texcoord();
  void read_normal();
  void read_face();
  // The float in words_[k], `what` naming it for errors.
  float number(std::size_t k, const char* what) const;
  std::int64_t read_index(std::string_view token, std::size_t defined, const char* kind,
                          std::size_t corner) const;
  std::vector<FaceGroup> groups() const;
  // Throws `code` for the current line: field "line N", message "line N: <message>".
  [[noreturn]] void fail(ErrorCode code, const std::string& message) const {
    throw_at(code, line_field(line_), message);
  }

  std::size_t line_ = 0;                 // the line being read
  std::vector<std::string_view> words_;  // of the current line
  std::vector<std::int64_t> vertices_;   // of the current face
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec2> texcoords_;
  std::vector<glm::vec3> normals_;
  std::vector<Corner> corners_;
  std::vector<Face> faces_;
  NameTable g_names_;
  NameTable o_names_;
  std::size_t g_ = 0;
  std::size_t o_ = 0;
};

void ObjReader::read(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  LineReader lines(text);
  TextLine line;
  while (lines.next(line)) {
    const std::string_view content = trim(strip_comment(line.text));
    if (content.empty()) continue;
    line_ = line.number;
    read_line(content);
  }
}

void ObjReader::read_line(std::string_view content) {
  if (content.back() == '\\') {
    fail(ErrorCode::kFormat, "line continuation ('\\' at the end) is not supported");
  }
  split_words(content, words_);
  const std::string_view keyword = words_[0];
  if (keyword == "v") {
    read_vertex();
  } else if (keyword == "vt") {
    read_texcoord();
  } else if (keyword == "vn") {
    read_normal();
  } else if (keyword == "f") {
    read_face();
  } else if (keyword == "g") {
    g_ = g_names_.intern(trim(content.substr(1)));
  } else if (keyword == "o") {
    o_ = o_names_.intern(trim(content.substr(1)));
  } else if (contains(kFreeForm, keyword)) {
    fail(ErrorCode::kFormat,
         "free-form geometry (" + shown(keyword) + ") is not supported, only polygons");
  } else if (!contains(kIgnored, keyword)) {
    fail(ErrorCode::kFormat, "unknown statement " + shown(keyword));
  }
}

float ObjReader::number(std::size_t k, const char* what) const {
  float value = 0.0f;
  const NumberError error = parse_float(words_[k], value);
  if (error != NumberError::kNone) throw_float_error(error, words_[k], line_field(line_), what);
  return value;
}

void ObjReader::read_vertex() {
  const std::size_t n = words_.size() - 1;
  if (n != 3 && n != 4 && n != 6 && n != 7) {
    fail(ErrorCode::kFormat, "'v' needs x y z, optionally followed by w, r g b or w r g b; found " +
                                 std::to_string(n) + " numbers");
  }
  static const char* const kNames[] = {"'v' x", "'v' y", "'v' z", "'v' extra value"};
  glm::vec3 p(0.0f);
  for (std::size_t k = 0; k < n; ++k) {
    const float value = number(k + 1, kNames[k < 3 ? k : 3]);
    if (k < 3) p[static_cast<int>(k)] = value;
  }
  positions_.push_back(p);
}

void ObjReader::read_texcoord() {
  const std::size_t n = words_.size() - 1;
  if (n < 1 || n > 3) {
    fail(ErrorCode::kFormat,
         "'vt' needs u, optionally v and w; found " + std::to_string(n) + " numbers");
  }
  static const char* const kNames[] = {"'vt' u", "'vt' v", "'vt' w"};
  glm::vec2 t(0.0f);
  for (std::size_t k = 0; k < n; ++k) {
    const float value = number(k + 1, kNames[k]);
    if (k < 2) t[static_cast<int>(k)] = value;
  }
  texcoords_.push_back(t);
}

void ObjReader::read_normal() {
  if (words_.size() != 4) {
    fail(ErrorCode::kFormat,
         "'vn' needs x y z; found " + std::to_string(words_.size() - 1) + " numbers");
  }
  static const char* const kNames[] = {"'vn' x", "'vn' y", "'vn' z"};
  glm::vec3 n(0.0f);
  for (std::size_t k = 0; k < 3; ++k) n[static_cast<int>(k)] = number(k + 1, kNames[k]);
  normals_.push_back(n);
}

// A 0-based index from an OBJ index `token` of `kind` ("v", "vt", "vn") at face
// corner `corner` (from 1). Negative indices count back from the `defined`
// statements so far and must land on one; positive ones are range-checked in
// build(), as they may refer forward.
std::int64_t ObjReader::read_index(std::string_view token, std::size_t defined, const char* kind,
                                   std::size_t corner) const {
  const auto fail_index = [&](ErrorCode code, const std::string& text) {
    fail(code, "face corner " + std::to_string(corner) + ": " + kind + " index " + text);
  };
  std::int64_t value = 0;
  const NumberError error = parse_int(token, value);
  if (error == NumberError::kUnreadable)
    fail_index(ErrorCode::kFormat, shown(token) + " is not an integer");
  if (error == NumberError::kOutOfRange)
    fail_index(ErrorCode::kInvalidMesh, shown(token) + " is out of range");
  if (value == 0) fail_index(ErrorCode::kInvalidMesh, "0 is out of range (OBJ indices start at 1)");
  if (value > 0) return value - 1;
  const std::int64_t resolved = static_cast<std::int64_t>(defined) + value;
  if (resolved < 0) {
    fail_index(ErrorCode::kInvalidMesh, std::to_string(value) + " is out of range (" +
                                            std::to_string(defined) + " '" + kind +
                                            "' lines before it)");
  }
  return resolved;
}

void ObjReader::read_face() {
  const std::size_t n = words_.size() - 1;
  if (n < 3)
    fail(ErrorCode::kFormat, "face has " + std::to_string(n) + " corners, at least 3 needed");
  const Face face{line_, corners_.size(), n, g_, o_};
  vertices_.clear();
  for (std::size_t k = 1; k <= n; ++k) {
    const std::string_view token = words_[k];
    const auto fail_corner = [&](const char* text) {
      fail(ErrorCode::kFormat, "face corner " + std::to_string(k) + " " + shown(token) + text);
    };
    std::string_view parts[3];  // v, vt, vn
    std::size_t count = 0;
    for (std::size_t begin = 0;;) {
      if (count == 3) fail_corner(" has more than two '/'");
      const std::size_t slash = token.find('/', begin);
      parts[count++] = token.substr(begin, slash == std::string_view::npos ? slash : slash - begin);
      if (slash == std::string_view::npos) break;
      begin = slash + 1;
    }
    if (parts[0].empty() || (count == 2 && parts[1].empty()) || (count == 3 && parts[2].empty())) {
      fail_corner(" is not v, v/vt, v//vn or v/vt/vn");
    }
    Corner corner;
    corner.v = read_index(parts[0], positions_.size(), "v", k);
    if (count >= 2 && !parts[1].empty()) {
      corner.vt = read_index(parts[1], texcoords_.size(), "vt", k);
    }
    if (count == 3) corner.vn = read_index(parts[2], normals_.size(), "vn", k);
    corners_.push_back(corner);
    vertices_.push_back(corner.v);
  }
  if (const auto repeat = find_repeated_corner(vertices_)) {
    fail(ErrorCode::kInvalidMesh,
         "face uses vertex " + std::to_string(vertices_[repeat->first] + 1) + " at corners " +
             std::to_string(repeat->first + 1) + " and " + std::to_string(repeat->second + 1) +
             " (a polygon's corners must be distinct)");
  }
  faces_.push_back(face);
}

[[noreturn]] void throw_index_range(const Face& face, std::size_t k, const char* kind,
                                    std::int64_t index, std::size_t defined) {
  throw_at(ErrorCode::kInvalidMesh, line_field(face.line),
           "face corner " + std::to_string(k + 1) + ": " + kind + " index " +
               std::to_string(index + 1) + " is out of range (" + std::to_string(defined) + " '" +
               kind + "' lines in the file)");
}

Mesh ObjReader::build() const {
  if (positions_.empty()) {
    throw Error(ErrorCode::kFormat, "positions", "positions: no 'v' lines in the OBJ data");
  }
  MeshBuilder builder;
  for (const glm::vec3& p : positions_) builder.add_vertex(p);
  const auto in_range = [](std::int64_t index, std::size_t size) {
    return index >= 0 && static_cast<std::uint64_t>(index) < size;
  };
  std::vector<std::uint32_t> polygon;
  for (const Face& face : faces_) {
    polygon.clear();
    for (std::size_t k = 0; k < face.corner_count; ++k) {
      const Corner& c = corners_[face.first_corner + k];
      if (!in_range(c.v, positions_.size())) {
        throw_index_range(face, k, "v", c.v, positions_.size());
      }
      if (c.vt >= 0 && !in_range(c.vt, texcoords_.size())) {
        throw_index_range(face, k, "vt", c.vt, texcoords_.size());
      }
      if (c.vn >= 0 && !in_range(c.vn, normals_.size())) {
        throw_index_range(face, k, "vn", c.vn, normals_.size());
      }
      polygon.push_back(static_cast<std::uint32_t>(c.v));
    }
    for (std::size_t k = 0; k < face.corner_count; ++k) {
      const Corner& c = corners_[face.first_corner + k];
      const std::uint32_t v = polygon[k];
      if (c.vt >= 0) builder.add_texcoord(v, texcoords_[static_cast<std::size_t>(c.vt)]);
      if (c.vn >= 0) builder.add_normal(v, normals_[static_cast<std::size_t>(c.vn)]);
    }
    builder.add_polygon(polygon);
  }
  Mesh mesh = builder.finish();
  mesh.groups = groups();
  return mesh;
}

// The file's groups: its "g" lines, or its "o" lines when it has no "g" line. A group
// is the run of triangles from the faces after its line up to the next g (o) line;
// faces before the first such line, or after one without a name, are in no group;
// runs without triangles are dropped.
std::vector<FaceGroup> ObjReader::groups() const {
  const bool by_g = !g_names_.empty();
  const NameTable& names = by_g ? g_names_ : o_names_;
  std::vector<FaceGroup> groups;
  if (names.empty()) return groups;
  std::size_t triangle = 0;
  std::size_t last_id = 0;  // of groups.back(), compared instead of the (long?) names
  for (const Face& face : faces_) {
    const std::size_t count = face.corner_count - 2;
    const std::size_t id = by_g ? face.g : face.o;
    if (id != 0) {
      if (id == last_id &&
          groups.back().first_triangle + groups.back().triangle_count == triangle) {
        groups.back().triangle_count += count;
      } else {
        groups.push_back(FaceGroup{names.name(id), triangle, count});
        last_id = id;
      }
    }
    triangle += count;
  }
  return groups;
}

}  // namespace

Mesh read_obj(std::string_view text) {
  ObjReader reader;
  reader.read(text);
  return reader.build();
}

}  // namespace finflex::io

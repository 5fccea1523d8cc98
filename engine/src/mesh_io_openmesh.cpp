// OBJ, PLY, OFF and STL through OpenMesh's reader and writer modules.
//
// OpenMesh's readers and writers talk to a mesh through the BaseImporter and
// BaseExporter interfaces. Instead of going through an OpenMesh halfedge mesh (which
// rejects non-manifold faces, splitting their vertices, and so changes the vertex
// count and order), the classes below implement those interfaces directly on flat
// arrays: vertices come out exactly as the file lists them, polygons are
// fan-triangulated in file order, and writers see the Mesh's own arrays.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/BaseKernel.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "finflex/error.hpp"
#include "mesh_io_formats.hpp"

namespace finflex::io {
namespace {

namespace om = OpenMesh;
namespace omio = OpenMesh::IO;

// Float output precision for the text formats (OBJ, OFF): 9 significant digits
// round-trip every float exactly. (Through IOManager's stream interface the writers
// keep the stream's default float notation.)
constexpr std::streamsize kTextPrecision = std::numeric_limits<float>::max_digits10;

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

// OpenMesh's extension key for IOManager's stream interface.
const char* openmesh_extension(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj:
      return "obj";
    case MeshFormat::kPly:
      return "ply";
    case MeshFormat::kOff:
      return "off";
    case MeshFormat::kStl:
      return "stl";
    default:
      break;
  }
  throw Error(ErrorCode::kFormat, "path",
              std::string(format_name(format)) + " is not an OpenMesh format");
}

// OpenMesh's reader and writer modules are process-wide singletons with per-call
// state (and the log switch below is global): one OpenMesh read or write at a time.
std::mutex& openmesh_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Silences OpenMesh's log streams (omlog, omout, omerr) for its lifetime and then
// restores their previous state, dropping what was logged meanwhile. The switch is
// process-wide: concurrent OpenMesh users in other threads are silenced too.
class QuietOpenMesh {
 public:
  QuietOpenMesh()
      : log_enabled_(omlog().is_enabled()),
        out_enabled_(omout().is_enabled()),
        err_enabled_(omerr().is_enabled()) {
    omlog().disable();
    omout().disable();
    omerr().disable();
  }
  ~QuietOpenMesh() {
    // Flushing while disabled discards half-written lines instead of printing them later.
    omlog().flush();
    omout().flush();
    omerr().flush();
    if (log_enabled_) omlog().enable();
    if (out_enabled_) omout().enable();
    if (err_enabled_) omerr().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool log_enabled_;
  bool out_enabled_;
  bool err_enabled_;
};

glm::vec3 to_glm(const om::Vec3f& v) { return {v[0], v[1], v[2]}; }
glm::dvec3 to_glm(const om::Vec3d& v) { return {v[0], v[1], v[2]}; }
om::Vec3f to_om(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// ---------------------------------------------------------------------------------
// Reading

// Collects what an OpenMesh reader reports: vertices in file order, per-corner
// normals and texcoords folded into per-vertex ones, polygons fan-triangulated.
// Indices are stored as the reader passes them (possibly out of range); they are
// checked by take_mesh(), once the vertex count is final.
//
// Some readers trust the element counts in a file's header and keep adding the last
// element when the file is shorter (OFF). The importer therefore refuses more
// vertices or polygon corners than a file of its size can hold (a vertex takes at
// least 3 bytes, a corner at least 1 in every format) by throwing kFormat.
class MeshImporter final : public omio::BaseImporter {
 public:
  using BaseImporter::add_vertex;

  explicit MeshImporter(std::uintmax_t file_size)
      : max_vertices_(file_size / 3 + 16), max_corners_(file_size + 16) {}

  // The collected mesh; normals only if the file had some (vertices without one get
  // area-weighted normals). Throws kFormat / kInvalidMesh on bad faces or indices.
  Mesh take_mesh();

  om::VertexHandle add_vertex(const om::Vec3f& point) override {
    om::VertexHandle handle = add_vertex();
    positions_.back() = to_glm(point);
    return handle;
  }
  om::VertexHandle add_vertex() override {
    if (positions_.size() >= max_vertices_) throw_truncated("vertices");
    positions_.emplace_back(0.0f);
    normals_.emplace_back();
    texcoords_.emplace_back();
    return om::VertexHandle(static_cast<int>(positions_.size() - 1));
  }
  void set_point(om::VertexHandle vh, const om::Vec3f& point) override {
    if (is_vertex(vh)) positions_[vh.idx()] = to_glm(point);
  }
  void set_normal(om::VertexHandle vh, const om::Vec3f& normal) override {
    if (is_vertex(vh)) normals_[vh.idx()].add(glm::dvec3(to_glm(normal)));
  }
  void set_normal(om::VertexHandle vh, const om::Vec3d& normal) override {
    if (is_vertex(vh)) normals_[vh.idx()].add(to_glm(normal));
  }
  void set_texcoord(om::VertexHandle vh, const om::Vec2f& texcoord) override {
    if (!is_vertex(vh)) return;
    TexcoordSlot& slot = texcoords_[vh.idx()];
    if (slot.present) return;  // first one wins: a per-vertex texcoord cannot hold seams
    slot.present = true;
    slot.value = glm::vec2(texcoord[0], texcoord[1]);
  }

  om::FaceHandle add_face(const VHandles& polygon) override;
  om::FaceHandle add_face(om::HalfedgeHandle) override { return om::FaceHandle(); }

  // Header counts are capped by the file size: a corrupt count allocates nothing big.
  void reserve(unsigned int n_vertices, unsigned int, unsigned int n_faces) override {
    const auto nv = static_cast<std::size_t>(std::min<std::uintmax_t>(n_vertices, max_vertices_));
    positions_.reserve(nv);
    normals_.reserve(nv);
    texcoords_.reserve(nv);
    corners_.reserve(static_cast<std::size_t>(
        std::min<std::uintmax_t>(3u * std::uintmax_t{n_faces}, max_corners_)));
  }
  size_t n_vertices() const override { return positions_.size(); }
  size_t n_faces() const override { return corners_.size() / 3; }
  size_t n_edges() const override { return 0; }
  // Per polygon reported (in order): its corner count; its fan's triangles follow
  // those of the polygons before it.
  const std::vector<std::size_t>& polygon_sizes() const { return polygon_sizes_; }

  // Everything else a reader may report (colors, status, halfedge connectivity,
  // face normals such as STL's, 3D texcoords, materials) is not kept.
  om::HalfedgeHandle add_edge(om::VertexHandle, om::VertexHandle) override {
    return om::HalfedgeHandle();
  }
  void add_face_texcoords(om::FaceHandle, om::VertexHandle,
                          const std::vector<om::Vec2f>&) override {}
  void add_face_texcoords(om::FaceHandle, om::VertexHandle,
                          const std::vector<om::Vec3f>&) override {}
  void set_face_texindex(om::FaceHandle, int) override {}
  void set_halfedge(om::VertexHandle, om::HalfedgeHandle) override {}
  void set_color(om::VertexHandle, const om::Vec3uc&) override {}
  void set_color(om::VertexHandle, const om::Vec4uc&) override {}
  void set_color(om::VertexHandle, const om::Vec3f&) override {}
  void set_color(om::VertexHandle, const om::Vec4f&) override {}
  void set_status(om::VertexHandle, const om::Attributes::StatusInfo&) override {}
  void set_next(om::HalfedgeHandle, om::HalfedgeHandle) override {}
  void set_face(om::HalfedgeHandle, om::FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(om::HalfedgeHandle, const om::Vec2f&) override {}
  void set_texcoord(om::VertexHandle, const om::Vec3f&) override {}
  void set_texcoord(om::HalfedgeHandle, const om::Vec3f&) override {}
  void set_status(om::HalfedgeHandle, const om::Attributes::StatusInfo&) override {}
  void set_color(om::EdgeHandle, const om::Vec3uc&) override {}
  void set_color(om::EdgeHandle, const om::Vec4uc&) override {}
  void set_color(om::EdgeHandle, const om::Vec3f&) override {}
  void set_color(om::EdgeHandle, const om::Vec4f&) override {}
  void set_status(om::EdgeHandle, const om::Attributes::StatusInfo&) override {}
  void set_normal(om::FaceHandle, const om::Vec3f&) override {}
  void set_normal(om::FaceHandle, const om::Vec3d&) override {}
  void set_color(om::FaceHandle, const om::Vec3uc&) override {}
  void set_color(om::FaceHandle, const om::Vec4uc&) override {}
  void set_color(om::FaceHandle, const om::Vec3f&) override {}
  void set_color(om::FaceHandle, const om::Vec4f&) override {}
  void set_status(om::FaceHandle, const om::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  // The normals given for one vertex (OBJ gives one per face corner).
  struct NormalSlot {
    int count = 0;
    bool all_equal = true;
    glm::dvec3 first{0.0};
    glm::dvec3 sum{0.0};
    void add(const glm::dvec3& n) {
      if (count == 0) first = n;
      all_equal = all_equal && n == first;
      sum += n;
      ++count;
    }
  };
  struct TexcoordSlot {
    bool present = false;
    glm::vec2 value{0.0f};
  };

  [[noreturn]] static void throw_truncated(const char* what) {
    throw Error(ErrorCode::kFormat, "path",
                std::string("the reader reports more ") + what +
                    " than the file can hold (truncated file or wrong element count)");
  }
  bool is_vertex(om::VertexHandle vh) const {
    return vh.idx() >= 0 && static_cast<std::size_t>(vh.idx()) < positions_.size();
  }
  std::vector<std::uint32_t> checked_indices() const;
  void fill_normals(Mesh& mesh) const;

  std::uintmax_t max_vertices_;
  std::uintmax_t max_corners_;
  std::uintmax_t corner_count_ = 0;  // polygon corners reported so far
  std::vector<glm::vec3> positions_;
  std::vector<NormalSlot> normals_;
  std::vector<TexcoordSlot> texcoords_;
  std::vector<int> corners_;          // three vertex indices per triangle, unchecked
  std::vector<std::size_t> face_of_;  // per triangle: the file's polygon number
  std::size_t polygon_count_ = 0;
  std::vector<std::size_t> polygon_sizes_;
  std::string face_error_;  // first malformed polygon, if any
};

om::FaceHandle MeshImporter::add_face(const VHandles& polygon) {
  const std::size_t face = polygon_count_++;
  polygon_sizes_.push_back(polygon.size());
  corner_count_ += polygon.size();
  if (corner_count_ > max_corners_) throw_truncated("polygon corners");
  if (polygon.size() < 3) {
    if (face_error_.empty()) {
      face_error_ = "face " + std::to_string(face) + " has " + std::to_string(polygon.size()) +
                    " vertices (at least 3 needed)";
    }
    return om::FaceHandle();
  }
  const om::FaceHandle first_triangle(static_cast<int>(n_faces()));
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {  // fan around polygon[0]
    corners_.push_back(polygon[0].idx());
    corners_.push_back(polygon[k].idx());
    corners_.push_back(polygon[k + 1].idx());
    face_of_.push_back(face);
  }
  return first_triangle;
}

std::vector<std::uint32_t> MeshImporter::checked_indices() const {
  const std::size_t n = positions_.size();
  std::vector<std::uint32_t> indices(corners_.size());
  for (std::size_t i = 0; i < corners_.size(); ++i) {
    const int index = corners_[i];
    if (index < 0 || static_cast<std::size_t>(index) >= n) {
      const std::string field = "indices[" + std::to_string(i) + "]";
      throw Error(ErrorCode::kInvalidMesh, field,
                  field + " = " + std::to_string(index) + " is out of range (vertex count " +
                      std::to_string(n) + "; face " + std::to_string(face_of_[i / 3]) +
                      " of the file)");
    }
    indices[i] = static_cast<std::uint32_t>(index);
  }
  return indices;
}

// Per vertex: the file's normal if it gave one (or the same one for every corner),
// else the normalized mean of its corner normals; vertices without a usable file
// normal (none given, or a zero mean) get the area-weighted normal. Non-finite file
// normals are kept so that validation reports them.
void MeshImporter::fill_normals(Mesh& mesh) const {
  const bool any = std::any_of(normals_.begin(), normals_.end(),
                               [](const NormalSlot& s) { return s.count > 0; });
  if (!any) return;
  Mesh computed;
  computed.positions = mesh.positions;
  computed.indices = mesh.indices;
  compute_vertex_normals(computed);
  mesh.normals.resize(mesh.positions.size());
  for (std::size_t v = 0; v < normals_.size(); ++v) {
    const NormalSlot& slot = normals_[v];
    const glm::dvec3 n = slot.all_equal ? slot.first : slot.sum;
    const double length = glm::length(n);
    if (slot.count == 0 || length == 0.0) {
      mesh.normals[v] = computed.normals[v];
    } else {
      mesh.normals[v] = glm::vec3(n / length);  // NaN stays NaN
    }
  }
}

Mesh MeshImporter::take_mesh() {
  if (!face_error_.empty()) throw Error(ErrorCode::kFormat, "faces", face_error_);
  Mesh mesh;
  mesh.indices = checked_indices();
  mesh.positions = std::move(positions_);
  fill_normals(mesh);
  const bool any_texcoord = std::any_of(texcoords_.begin(), texcoords_.end(),
                                        [](const TexcoordSlot& s) { return s.present; });
  if (any_texcoord) {
    mesh.texcoords.reserve(texcoords_.size());
    for (const TexcoordSlot& slot : texcoords_) mesh.texcoords.push_back(slot.value);
  }
  return mesh;
}

// ---------------------------------------------------------------------------------
// OBJ groups
//
// OpenMesh's OBJ reader skips "g" and "o" lines, so a light second pass over the text
// finds them. It reads the face lines as that reader does (the first field of each
// corner; negative indices count back from the "v" lines so far; repeated vertices
// dropped; a face left with fewer than 3 is skipped) and checks that its faces match
// the importer's one to one, vertex for vertex, so that a group can never be put on
// the wrong triangles.

// One "f" line that the reader turns into a polygon.
struct ObjFace {
  std::size_t line = 0;        // 1-based
  std::size_t g = 0;           // 1 + index into ObjScan::g_names; 0: no group
  std::size_t o = 0;           // 1 + index into ObjScan::o_names; 0: no object
  bool readable = true;        // false: a corner the reader would read as garbage
  std::vector<long> vertices;  // 0-based, as the reader passes them (maybe out of range)
};

struct ObjScan {
  std::vector<std::string> g_names;
  std::vector<std::string> o_names;
  std::vector<ObjFace> faces;
};

// What the reader trims off both ends of a line.
constexpr const char* kObjTrimmed = " \t\r\n";

std::string trim_obj(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(kObjTrimmed);
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(kObjTrimmed) - begin + 1);
}

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// 1 + the index of `name` in `names` (added if new); 0 for an empty name.
std::size_t intern(std::vector<std::string>& names, const std::string& name) {
  if (name.empty()) return 0;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<std::size_t>(it - names.begin()) + 1;
  names.push_back(name);
  return names.size();
}

// A leading integer of `text`, as `stream >> int` reads it.
std::optional<long> leading_int(const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || errno == ERANGE || value < std::numeric_limits<int>::min() ||
      value > std::numeric_limits<int>::max()) {
    return std::nullopt;
  }
  return value;
}

// The corners of an "f" line (`rest`: the text after "f"), as the reader sees them.
void read_obj_face(const std::string& rest, long positions_so_far, ObjFace& face) {
  std::istringstream tokens(rest);
  std::string token;
  while (tokens >> token) {
    const std::size_t slash = token.find('/');
    const std::string first = token.substr(0, slash);
    if (first.empty()) continue;  // "/2/3": no position given
    const std::optional<long> value = leading_int(first);
    if (!value) {
      // Without '/', the reader skips the corner; with one, it keeps a stale value.
      if (slash != std::string::npos) face.readable = false;
      continue;
    }
    const long index = *value < 0 ? positions_so_far + *value : *value - 1;
    if (std::find(face.vertices.begin(), face.vertices.end(), index) == face.vertices.end()) {
      face.vertices.push_back(index);
    }
  }
}

ObjScan scan_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::kIo, "path", "cannot reopen the OBJ file to read its groups");
  ObjScan scan;
  std::size_t g = 0;
  std::size_t o = 0;
  long positions = 0;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const std::string text = trim_obj(line);
    if (text.empty() || text[0] == '#' || is_space(text[0])) continue;
    const std::size_t space =
        static_cast<std::size_t>(std::find_if(text.begin(), text.end(), is_space) - text.begin());
    const std::string keyword = text.substr(0, space);
    const std::string rest = trim_obj(text.substr(space));
    if (keyword == "v") {
      ++positions;
    } else if (keyword == "g") {
      g = intern(scan.g_names, rest);
    } else if (keyword == "o") {
      o = intern(scan.o_names, rest);
    } else if (keyword == "f") {
      ObjFace face;
      face.line = number;
      face.g = g;
      face.o = o;
      read_obj_face(rest, positions, face);
      if (face.vertices.size() >= 3 || !face.readable) scan.faces.push_back(std::move(face));
    }
  }
  if (in.bad()) throw Error(ErrorCode::kIo, "path", "reading the OBJ file's groups failed");
  return scan;
}

[[noreturn]] void throw_misaligned(const std::string& where) {
  throw Error(ErrorCode::kFormat, "groups",
              "groups: " + where +
                  " does not match the faces the OBJ reader reported, so the g/o groups "
                  "cannot be placed on the triangles");
}

// True if triangles [first, first + size - 2) of `indices` are the fan of `face`.
bool is_fan_of(const ObjFace& face, const std::vector<std::uint32_t>& indices, std::size_t first) {
  const auto& v = face.vertices;
  for (std::size_t k = 1; k + 1 < v.size(); ++k) {
    const std::size_t t = 3 * (first + k - 1);
    if (t + 2 >= indices.size() || static_cast<long>(indices[t]) != v[0] ||
        static_cast<long>(indices[t + 1]) != v[k] ||
        static_cast<long>(indices[t + 2]) != v[k + 1]) {
      return false;
    }
  }
  return true;
}

// The OBJ file's groups: its "g" lines, or its "o" lines when it has no "g" line. A
// group is the run of triangles from the faces after its line up to the next g (o)
// line; faces before the first such line, or after one without a name, are in no
// group; runs without triangles are dropped. `polygon_sizes` and `indices` are what
// the importer collected from the same file.
std::vector<FaceGroup> obj_groups(const std::string& path,
                                  const std::vector<std::size_t>& polygon_sizes,
                                  const std::vector<std::uint32_t>& indices) {
  const ObjScan scan = scan_obj(path);
  const bool by_g = !scan.g_names.empty();
  const std::vector<std::string>& names = by_g ? scan.g_names : scan.o_names;
  std::vector<FaceGroup> groups;
  if (names.empty()) return groups;
  if (scan.faces.size() != polygon_sizes.size()) {
    throw_misaligned(std::to_string(scan.faces.size()) + " face lines against " +
                     std::to_string(polygon_sizes.size()) + " polygons read");
  }
  std::size_t triangle = 0;
  for (std::size_t p = 0; p < scan.faces.size(); ++p) {
    const ObjFace& face = scan.faces[p];
    if (!face.readable || face.vertices.size() != polygon_sizes[p] ||
        !is_fan_of(face, indices, triangle)) {
      throw_misaligned("the face on line " + std::to_string(face.line));
    }
    const std::size_t count = polygon_sizes[p] - 2;
    const std::size_t id = by_g ? face.g : face.o;
    if (id != 0) {
      const std::string& name = names[id - 1];
      if (!groups.empty() && groups.back().name == name &&
          groups.back().first_triangle + groups.back().triangle_count == triangle) {
        groups.back().triangle_count += count;
      } else {
        groups.push_back(FaceGroup{name, triangle, count});
      }
    }
    triangle += count;
  }
  return groups;
}

// ---------------------------------------------------------------------------------
// Writing

// Serves a validated Mesh (with normals) to OpenMesh's writers: vertex i is
// VertexHandle(i), triangle t is FaceHandle(t); face normals are the unit triangle
// normals (STL). Colors, status and halfedge data report defaults.
class MeshExporter final : public omio::BaseExporter {
 public:
  explicit MeshExporter(const Mesh& mesh)
      : mesh_(mesh), face_normals_(face_normals(mesh.positions, mesh.indices)) {}

  om::Vec3f point(om::VertexHandle vh) const override { return to_om(mesh_.positions[vh.idx()]); }
  om::Vec3d pointd(om::VertexHandle vh) const override { return om::Vec3d(point(vh)); }
  bool is_point_double() const override { return false; }
  om::Vec3f normal(om::VertexHandle vh) const override { return to_om(mesh_.normals[vh.idx()]); }
  om::Vec3d normald(om::VertexHandle vh) const override { return om::Vec3d(normal(vh)); }
  bool is_normal_double() const override { return false; }
  om::Vec2f texcoord(om::VertexHandle vh) const override {
    if (mesh_.texcoords.empty()) return om::Vec2f(0.0f, 0.0f);
    const glm::vec2& t = mesh_.texcoords[vh.idx()];
    return om::Vec2f(t.x, t.y);
  }
  om::Vec2f texcoord(om::HalfedgeHandle) const override { return om::Vec2f(0.0f, 0.0f); }

  unsigned int get_vhandles(om::FaceHandle fh,
                            std::vector<om::VertexHandle>& vhandles) const override {
    const std::size_t base = 3 * static_cast<std::size_t>(fh.idx());
    vhandles.clear();
    for (std::size_t k = 0; k < 3; ++k) {
      vhandles.emplace_back(static_cast<int>(mesh_.indices[base + k]));
    }
    return 3;
  }
  om::HalfedgeHandle getHeh(om::FaceHandle, om::VertexHandle) const override {
    return om::HalfedgeHandle();
  }
  unsigned int get_face_texcoords(std::vector<om::Vec2f>&) const override { return 0; }
  om::Vec3f normal(om::FaceHandle fh) const override { return om::Vec3f(normald(fh)); }
  om::Vec3d normald(om::FaceHandle fh) const override {
    const glm::dvec3& n = face_normals_[fh.idx()];
    return om::Vec3d(n.x, n.y, n.z);
  }

  om::Vec3uc color(om::VertexHandle) const override { return om::Vec3uc(0, 0, 0); }
  om::Vec4uc colorA(om::VertexHandle) const override { return om::Vec4uc(0, 0, 0, 255); }
  om::Vec3ui colori(om::VertexHandle) const override { return om::Vec3ui(0, 0, 0); }
  om::Vec4ui colorAi(om::VertexHandle) const override { return om::Vec4ui(0, 0, 0, 255); }
  om::Vec3f colorf(om::VertexHandle) const override { return om::Vec3f(0.0f, 0.0f, 0.0f); }
  om::Vec4f colorAf(om::VertexHandle) const override { return om::Vec4f(0.0f, 0.0f, 0.0f, 1.0f); }
  om::Attributes::StatusInfo status(om::VertexHandle) const override { return {}; }
  om::Vec3uc color(om::FaceHandle) const override { return om::Vec3uc(0, 0, 0); }
  om::Vec4uc colorA(om::FaceHandle) const override { return om::Vec4uc(0, 0, 0, 255); }
  om::Vec3ui colori(om::FaceHandle) const override { return om::Vec3ui(0, 0, 0); }
  om::Vec4ui colorAi(om::FaceHandle) const override { return om::Vec4ui(0, 0, 0, 255); }
  om::Vec3f colorf(om::FaceHandle) const override { return om::Vec3f(0.0f, 0.0f, 0.0f); }
  om::Vec4f colorAf(om::FaceHandle) const override { return om::Vec4f(0.0f, 0.0f, 0.0f, 1.0f); }
  om::Attributes::StatusInfo status(om::FaceHandle) const override { return {}; }
  om::Vec3uc color(om::EdgeHandle) const override { return om::Vec3uc(0, 0, 0); }
  om::Vec4uc colorA(om::EdgeHandle) const override { return om::Vec4uc(0, 0, 0, 255); }
  om::Vec3ui colori(om::EdgeHandle) const override { return om::Vec3ui(0, 0, 0); }
  om::Vec4ui colorAi(om::EdgeHandle) const override { return om::Vec4ui(0, 0, 0, 255); }
  om::Vec3f colorf(om::EdgeHandle) const override { return om::Vec3f(0.0f, 0.0f, 0.0f); }
  om::Vec4f colorAf(om::EdgeHandle) const override { return om::Vec4f(0.0f, 0.0f, 0.0f, 1.0f); }
  om::Attributes::StatusInfo status(om::EdgeHandle) const override { return {}; }
  int get_halfedge_id(om::VertexHandle) override { return -1; }
  int get_halfedge_id(om::FaceHandle) override { return -1; }
  int get_next_halfedge_id(om::HalfedgeHandle) override { return -1; }
  int get_to_vertex_id(om::HalfedgeHandle) override { return -1; }
  int get_face_id(om::HalfedgeHandle) override { return -1; }
  om::Attributes::StatusInfo status(om::HalfedgeHandle) const override { return {}; }

  // The PLY writer lists the kernel's custom properties: an empty kernel has none.
  const om::BaseKernel* kernel() override { return &no_properties_; }

  size_t n_vertices() const override { return mesh_.positions.size(); }
  size_t n_faces() const override { return mesh_.indices.size() / 3; }
  size_t n_edges() const override { return 0; }
  bool is_triangle_mesh() const override { return true; }
  bool has_vertex_normals() const override { return true; }
  bool has_vertex_texcoords() const override { return !mesh_.texcoords.empty(); }
  bool has_face_normals() const override { return true; }

 private:
  const Mesh& mesh_;
  std::vector<glm::dvec3> face_normals_;
  om::BaseKernel no_properties_;
};

// What each format is asked to write. OBJ and OFF are text; PLY and STL binary
// (little endian), which keeps floats exact. STL has no per-vertex data at all.
omio::Options write_options(MeshFormat format, const Mesh& mesh) {
  omio::Options options;
  if (format == MeshFormat::kPly || format == MeshFormat::kStl) {
    options += omio::Options::Binary;
    options += omio::Options::LSB;
  }
  if (format != MeshFormat::kStl) {
    options += omio::Options::VertexNormal;
    if (!mesh.texcoords.empty()) options += omio::Options::VertexTexCoord;
  }
  return options;
}

}  // namespace

Mesh read_openmesh(const std::string& path, MeshFormat format) {
  const std::string name = format_name(format);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  MeshImporter importer(ec ? std::uintmax_t{0} : size);
  omio::Options options;
  options += omio::Options::VertexNormal;
  options += omio::Options::VertexTexCoord;
  bool ok = false;
  {
    const std::lock_guard<std::mutex> lock(openmesh_mutex());
    QuietOpenMesh quiet;
    ok = omio::IOManager().read(path, importer, options);
  }
  if (!ok) {
    throw Error(ErrorCode::kFormat, "path", "not a readable " + name + " file");
  }
  if (importer.n_vertices() == 0) {
    throw Error(ErrorCode::kFormat, "positions", "no vertices found in the " + name + " data");
  }
  Mesh mesh = importer.take_mesh();
  if (format == MeshFormat::kObj) {
    mesh.groups = obj_groups(path, importer.polygon_sizes(), mesh.indices);
  }
  return mesh;
}

void write_openmesh(std::ostream& out, MeshFormat format, const Mesh& mesh) {
  MeshExporter exporter(mesh);
  bool ok = false;
  {
    const std::lock_guard<std::mutex> lock(openmesh_mutex());
    QuietOpenMesh quiet;
    ok = omio::IOManager().write(out, openmesh_extension(format), exporter,
                                 write_options(format, mesh), kTextPrecision);
  }
  if (!ok) {
    throw Error(ErrorCode::kIo, "path",
                std::string("OpenMesh's ") + format_name(format) + " writer failed");
  }
}

}  // namespace finflex::io

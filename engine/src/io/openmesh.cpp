// OBJ, PLY, OFF and STL writing through OpenMesh's writer modules.
//
// OpenMesh's writers talk to a mesh through the BaseExporter interface. Instead of
// going through an OpenMesh halfedge mesh (which rejects non-manifold faces,
// splitting their vertices, and so changes the vertex count and order), the class
// below implements that interface directly on the Mesh's own arrays. (Reading is
// done by our own strict readers, mesh_io_obj.cpp and the others.)
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/BaseKernel.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <cstddef>
#include <limits>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "io/formats.hpp"

namespace finflex::io {
namespace {

namespace om = OpenMesh;
namespace omio = OpenMesh::IO;

// Float output precision for the text formats (OBJ, OFF): 9 significant digits
// round-trip every float exactly. (Through IOManager's stream interface the writers
// keep the stream's default float notation.)
constexpr std::streamsize kTextPrecision = std::numeric_limits<float>::max_digits10;

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

// OpenMesh's writer modules are process-wide singletons with per-call state (and the
// log switch below is global): one OpenMesh write at a time.
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

om::Vec3f to_om(const glm::vec3& v) { return {v.x, v.y, v.z}; }

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

// Meshes (finflex/mesh.hpp, mesh_io.hpp) and body frames (finflex/body_frame.hpp).
#include <cstring>
#include <optional>

#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include "arrays.hpp"

namespace finflex::python {
namespace {

using Tuple3 = std::tuple<double, double, double>;
Tuple3 to_tuple(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
glm::dvec3 from_tuple(const Tuple3& t) { return {std::get<0>(t), std::get<1>(t), std::get<2>(t)}; }

// A read-only (rows, columns) view of a mesh attribute, owned by the mesh's object.
template <typename T, std::size_t Columns>
nb::ndarray<nb::numpy, const T, nb::shape<-1, Columns>> rows_view(const T* data, std::size_t rows,
                                                                  nb::handle owner) {
  const std::size_t shape[2] = {rows, Columns};
  return nb::ndarray<nb::numpy, const T, nb::shape<-1, Columns>>(data, 2, shape, owner);
}

Mesh make_mesh(nb::handle positions, nb::handle indices, nb::handle normals) {
  Mesh mesh;
  const std::vector<float> p = float_rows(positions, "positions", 3);
  mesh.positions.resize(p.size() / 3);
  if (!p.empty()) std::memcpy(mesh.positions.data(), p.data(), p.size() * sizeof(float));
  mesh.indices = index_rows(indices, "indices", 3);
  if (normals.is_none()) {
    compute_vertex_normals(mesh);
  } else {
    const std::vector<float> n = float_rows(normals, "normals", 3);
    mesh.normals.resize(n.size() / 3);
    if (!n.empty()) std::memcpy(mesh.normals.data(), n.data(), n.size() * sizeof(float));
  }
  validate_mesh(mesh);
  return mesh;
}

}  // namespace

void bind_mesh(nb::module_& m) {
  nb::class_<Mesh>(m, "Mesh",
                   "A triangle mesh: the rest shape FinFlex deforms, or a deformed instance. "
                   "Its arrays are read-only views.")
      .def(
          "__init__",
          [](Mesh* self, nb::handle positions, nb::handle indices, nb::handle normals) {
            new (self) Mesh(make_mesh(positions, indices, normals));
          },
          nb::arg("positions"), nb::arg("indices"), nb::arg("normals").none() = nb::none(),
          nb::sig("def __init__(self, positions: numpy.typing.ArrayLike, indices: "
                  "numpy.typing.ArrayLike, normals: numpy.typing.ArrayLike | None = None) -> None"),
          "A mesh from arrays: positions float32 (V, 3), indices uint32 (T, 3) counter-"
          "clockwise seen from outside, unit normals float32 (V, 3) or None (area-weighted "
          "ones are computed). Validated (finflex.Error naming e.g. 'positions[12].y').")
      .def_prop_ro("vertex_count", &Mesh::vertex_count)
      .def_prop_ro("triangle_count", &Mesh::triangle_count)
      .def_prop_ro(
          "positions",
          [](nb::handle_t<Mesh> self) {
            const Mesh& mesh = nb::cast<const Mesh&>(self);
            return rows_view<float, 3>(reinterpret_cast<const float*>(mesh.positions.data()),
                                       mesh.vertex_count(), self);
          },
          "Vertex positions, float32 (V, 3).")
      .def_prop_ro(
          "normals",
          [](nb::handle_t<Mesh> self) {
            const Mesh& mesh = nb::cast<const Mesh&>(self);
            return rows_view<float, 3>(reinterpret_cast<const float*>(mesh.normals.data()),
                                       mesh.normals.size(), self);
          },
          "Unit vertex normals, float32 (V, 3).")
      .def_prop_ro(
          "tangents",
          [](nb::handle_t<Mesh> self)
              -> std::optional<nb::ndarray<nb::numpy, const float, nb::shape<-1, 4>>> {
            const Mesh& mesh = nb::cast<const Mesh&>(self);
            if (!mesh.has_tangents()) return std::nullopt;
            return rows_view<float, 4>(reinterpret_cast<const float*>(mesh.tangents.data()),
                                       mesh.tangents.size(), self);
          },
          "Tangents float32 (V, 4): xyz unit tangent, w the bitangent sign; None if absent.")
      .def_prop_ro(
          "indices",
          [](nb::handle_t<Mesh> self) {
            const Mesh& mesh = nb::cast<const Mesh&>(self);
            return rows_view<std::uint32_t, 3>(mesh.indices.data(), mesh.triangle_count(), self);
          },
          "Triangles, uint32 (T, 3).")
      .def(
          "save", [](const Mesh& mesh, const std::string& path) { save_mesh(path, mesh); },
          nb::arg("path"),
          "Writes the mesh (format by extension: .obj .ply .off .stl .gltf .glb); on error "
          "the file is neither created nor changed.")
      .def("__repr__", [](const Mesh& mesh) {
        return "finflex.Mesh(" + std::to_string(mesh.vertex_count()) + " vertices, " +
               std::to_string(mesh.triangle_count()) + " triangles)";
      });

  m.def("load_mesh", &load_mesh, nb::arg("path"),
        "Loads a triangle mesh (.obj .ply .off .stl .gltf .glb); finflex.Error with code "
        "'io', 'format' or 'invalid_mesh' and the path in the message.");
  m.def("save_mesh", &save_mesh, nb::arg("path"), nb::arg("mesh"),
        "Writes a mesh; on error the file is neither created nor changed.");

  nb::class_<BodyFrame>(m, "BodyFrame",
                        "The local frame of a transform: spine axis_x towards the head, dorsal "
                        "axis_y, lateral axis_z, the pivot origin, the body's extent length.")
      .def(nb::init<>())
      .def_static("identity", &BodyFrame::identity,
                  "The mesh coordinates already are the body frame.")
      .def_prop_rw(
          "origin", [](const BodyFrame& f) { return to_tuple(f.origin); },
          [](BodyFrame& f, const Tuple3& v) { f.origin = from_tuple(v); })
      .def_prop_rw(
          "axis_x", [](const BodyFrame& f) { return to_tuple(f.axis_x); },
          [](BodyFrame& f, const Tuple3& v) { f.axis_x = from_tuple(v); })
      .def_prop_rw(
          "axis_y", [](const BodyFrame& f) { return to_tuple(f.axis_y); },
          [](BodyFrame& f, const Tuple3& v) { f.axis_y = from_tuple(v); })
      .def_prop_rw(
          "axis_z", [](const BodyFrame& f) { return to_tuple(f.axis_z); },
          [](BodyFrame& f, const Tuple3& v) { f.axis_z = from_tuple(v); })
      .def_rw("length", &BodyFrame::length)
      .def("validate", &BodyFrame::validate,
           "Raises finflex.Error naming the field when the frame is not orthonormal, "
           "right-handed, finite, with length > 0.");

  m.def(
      "find_body_frame",
      [](const Mesh& mesh, std::optional<Tuple3> head, std::optional<Tuple3> dorsal,
         std::optional<Tuple3> pivot) {
        FrameOptions options;
        if (head) options.head_direction = from_tuple(*head);
        if (dorsal) options.dorsal_direction = from_tuple(*dorsal);
        if (pivot) options.pivot = from_tuple(*pivot);
        return find_body_frame(mesh, options);
      },
      nb::arg("mesh"), nb::arg("head_direction") = nb::none(),
      nb::arg("dorsal_direction") = nb::none(), nb::arg("pivot") = nb::none(),
      "The body frame found from the mesh (principal axes, head, dorsal side, pivot, "
      "length); each direction or the pivot given overrides what is found.");
}

}  // namespace finflex::python

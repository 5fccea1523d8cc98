// Host outputs as numpy views.
#include "outputs.hpp"

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

namespace finflex::python {
namespace {

// The batch in mesh order: planes indexed by mesh vertex (no copy when it already is).
template <typename T>
DeformedBatch<T> in_mesh_order(DeformedBatch<T> batch) {
  if (batch.slot_of_vertex.empty()) return batch;
  DeformedBatch<T> out;
  BatchShape shape = batch.shape;
  shape.plane_stride = padded_plane_stride(shape.vertex_count);
  out.resize(shape);
  const bool previous = !batch.previous_positions.empty();
  if (previous) out.previous_positions.assign(shape.attribute_elements(), T(0));
  for (std::size_t i = 0; i < shape.instance_count; ++i) {
    for (std::size_t v = 0; v < shape.vertex_count; ++v) {
      out.scatter(out.positions, i, v, batch.position(i, v));
      out.scatter(out.normals, i, v, batch.normal(i, v));
      if (shape.tangents) out.scatter(out.tangents, i, v, batch.tangent(i, v));
      if (previous) out.scatter(out.previous_positions, i, v, batch.previous_position(i, v));
    }
  }
  return out;
}

template <typename T>
Array3 plane_view(const DeformedBatch<T>& batch, int attribute, nb::handle owner) {
  const std::vector<T>& data = attribute == 0   ? batch.positions
                               : attribute == 1 ? batch.normals
                               : attribute == 2 ? batch.tangents
                                                : batch.previous_positions;
  const BatchShape& l = batch.shape;
  const std::size_t shape[3] = {l.instance_count, l.vertex_count, 3};
  const std::int64_t plane = static_cast<std::int64_t>(l.plane_stride);
  const std::int64_t strides[3] = {3 * plane, 1, plane};
  return Array3(const_cast<T*>(data.data()), 3, shape, owner, strides, nb::dtype<T>());
}

}  // namespace

Outputs::Outputs(DeformedBatch<float> batch, std::shared_ptr<const RiggedMesh> model)
    : batch_(in_mesh_order(std::move(batch))), model_(std::move(model)) {}
Outputs::Outputs(DeformedBatch<double> batch, std::shared_ptr<const RiggedMesh> model)
    : batch_(in_mesh_order(std::move(batch))), model_(std::move(model)) {}

const BatchShape& Outputs::shape() const {
  return std::visit([](const auto& b) -> const BatchShape& { return b.shape; }, batch_);
}

Array3 Outputs::view(nb::handle self, int attribute) const {
  return std::visit([&](const auto& b) { return plane_view(b, attribute, self); }, batch_);
}

Array3 Outputs::positions(nb::handle self) const { return view(self, 0); }
Array3 Outputs::normals(nb::handle self) const { return view(self, 1); }
std::optional<Array3> Outputs::tangents(nb::handle self) const {
  if (!shape().tangents) return std::nullopt;
  return view(self, 2);
}
std::optional<Array3> Outputs::previous_positions(nb::handle self) const {
  const bool written =
      std::visit([](const auto& b) { return !b.previous_positions.empty(); }, batch_);
  if (!written) return std::nullopt;
  return view(self, 3);
}

Mesh Outputs::instance_mesh(std::size_t instance) const {
  return std::visit(
      [&](const auto& b) { return finflex::instance_mesh(model_->mesh(), b, instance); }, batch_);
}

void bind_outputs(nb::module_& m) {
  nb::class_<Outputs>(m, "Outputs",
                      "Deformed instances on the host (Deformer.read: float32; "
                      "deform_reference: float64). Arrays are views of this object's memory.")
      .def_prop_ro("instance_count", [](const Outputs& o) { return o.shape().instance_count; })
      .def_prop_ro("vertex_count", [](const Outputs& o) { return o.shape().vertex_count; })
      .def_prop_ro(
          "positions",
          [](nb::handle_t<Outputs> self) { return nb::cast<const Outputs&>(self).positions(self); },
          "Positions, shape (instances, vertices, 3), mesh vertex order (a strided view).")
      .def_prop_ro(
          "normals",
          [](nb::handle_t<Outputs> self) { return nb::cast<const Outputs&>(self).normals(self); },
          "Unit normals, shape (instances, vertices, 3).")
      .def_prop_ro(
          "tangents",
          [](nb::handle_t<Outputs> self) { return nb::cast<const Outputs&>(self).tangents(self); },
          "Unit tangents, shape (instances, vertices, 3), or None when the mesh has none.")
      .def_prop_ro(
          "previous_positions",
          [](nb::handle_t<Outputs> self) {
            return nb::cast<const Outputs&>(self).previous_positions(self);
          },
          "The frame before's positions, shape (instances, vertices, 3), where the batch's "
          "layout writes them (Batch.layout.previous_positions), else None.")
      .def("instance_mesh", &Outputs::instance_mesh, nb::arg("instance"),
           "The rest mesh with this instance's positions, normals and tangents.")
      .def(
          "save",
          [](const Outputs& o, std::size_t instance, const std::string& path) {
            save_mesh(path, o.instance_mesh(instance));
          },
          nb::arg("instance"), nb::arg("path"),
          "Writes one instance as a mesh file (format by extension: .obj .ply .off .stl "
          ".gltf .glb); on error the file is neither created nor changed.");
}

}  // namespace finflex::python

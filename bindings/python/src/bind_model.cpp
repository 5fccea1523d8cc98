// Rig files, models (a mesh with its rig) and per-instance parameters.
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"

namespace finflex::python {
namespace {

std::size_t index_of(const RiggedMesh& model, const std::string& name) {
  return model.rig().param_index(name);
}

}  // namespace

void bind_model(nb::module_& m) {
  nb::class_<RigSpec>(m, "Rig",
                      "A rig file (docs/rigs.md): components, frames and deformer chains, "
                      "not yet resolved against a mesh (finflex.Model does that).")
      .def_prop_ro("component_names", [](const RigSpec& spec) {
        std::vector<std::string> names;
        for (const ComponentSpec& c : spec.components) names.push_back(c.name);
        return names;
      });
  m.def("load_rig", &load_rig_file, nb::arg("path"),
        "Reads a rig file (JSON); finflex.Error naming the place, e.g. "
        "\"components[1] 'tail'.select.box.min\".");
  m.def("parse_rig", &parse_rig_json, nb::arg("json"), "Parses a rig from JSON text.");

  nb::class_<RigParameter>(m, "Parameter", "A per-instance parameter of a model's rig.")
      .def_ro("name", &RigParameter::name)
      .def_ro("offset", &RigParameter::offset, "Its first value's column in a parameter row.")
      .def_ro("count", &RigParameter::count, "Values it takes (1 for a bend's m).")
      .def_ro("limit", &RigParameter::limit, "The largest |value| accepted.")
      .def_ro("limit_source", &RigParameter::limit_source, "Which stage sets the limit.")
      .def("__repr__", [](const RigParameter& p) {
        return "finflex.Parameter('" + p.name + "', offset=" + std::to_string(p.offset) +
               ", count=" + std::to_string(p.count) + ", limit=" + std::to_string(p.limit) + ")";
      });

  nb::class_<PyModel>(m, "Model",
                      "What a job deforms: a rest mesh with its rig (finflex::RiggedMesh), "
                      "validated once.")
      .def(
          "__init__",
          [](PyModel* self, const Mesh& mesh, const RigSpec& rig) {
            new (self) PyModel{std::make_shared<const RiggedMesh>(mesh, resolve_rig(rig, mesh))};
          },
          nb::arg("mesh"), nb::arg("rig"),
          "A rig resolved against a mesh; finflex.Error naming the place at fault.")
      .def_static(
          "single_bend",
          [](const Mesh& mesh, std::optional<BodyFrame> frame, const std::string& mode) {
            const BendMode parsed = parse_bend_mode(mode);
            return PyModel{std::make_shared<const RiggedMesh>(
                RiggedMesh::single_bend(mesh, frame ? *frame : find_body_frame(mesh), parsed))};
          },
          nb::arg("mesh"), nb::arg("frame") = nb::none(), nb::arg("mode") = "exact",
          "The paper's whole-body bend, parameter 'm': mode 'exact' (closed form, the spine "
          "keeps its length) or 'paper' (the series (15)-(17)); frame None: found from the "
          "mesh.")
      .def_prop_ro("vertex_count", [](const PyModel& p) { return p.model->vertex_count(); })
      .def_prop_ro(
          "values_per_instance", [](const PyModel& p) { return p.model->values_per_instance(); },
          "Columns of a parameter row.")
      .def_prop_ro("parameters", [](const PyModel& p) { return p.model->rig().parameters; })
      .def_prop_ro("parameter_names",
                   [](const PyModel& p) {
                     std::vector<std::string> names;
                     for (const RigParameter& q : p.model->rig().parameters)
                       names.push_back(q.name);
                     return names;
                   })
      .def(
          "parameter_index",
          [](const PyModel& p, const std::string& name) { return index_of(*p.model, name); },
          nb::arg("name"), "A parameter's index by name; finflex.Error for an unknown one.")
      .def_prop_ro(
          "mesh", [](const PyModel& p) { return p.model->mesh(); }, "A copy of the rest mesh.")
      .def_prop_ro("is_single_bend", [](const PyModel& p) { return p.model->is_single_bend(); });

  nb::class_<PyParameters>(m, "Parameters",
                           "Per-instance parameter values of a model: instance_count rows of "
                           "values_per_instance float32, zeros (the rest pose) at first.")
      .def(
          "__init__",
          [](PyParameters* self, const PyModel& model, std::size_t instances) {
            new (self) PyParameters{model.model, RigParameters(*model.model, instances)};
          },
          nb::arg("model"), nb::arg("instances"))
      .def_prop_ro("instance_count",
                   [](const PyParameters& p) { return p.values.instance_count(); })
      .def_prop_ro(
          "values",
          [](nb::handle_t<PyParameters> self) {
            PyParameters& p = nb::cast<PyParameters&>(self);
            const std::size_t shape[2] = {p.values.instance_count(),
                                          p.values.values_per_instance()};
            return nb::ndarray<nb::numpy, float, nb::shape<-1, -1>>(p.values.values().data(), 2,
                                                                    shape, self);
          },
          "The values, float32 (instances, values_per_instance), writable, without a copy: "
          "fill them each frame.")
      .def(
          "set",
          [](PyParameters& p, std::size_t instance, const std::string& name, float value) {
            p.values.set(instance, name, value);
          },
          nb::arg("instance"), nb::arg("name"), nb::arg("value"),
          "Sets a one-value parameter by name; finflex.Error for an unknown name or instance.")
      .def(
          "set",
          [](PyParameters& p, std::size_t instance, const std::string& name,
             const std::vector<float>& values) { p.values.set(instance, name, values); },
          nb::arg("instance"), nb::arg("name"), nb::arg("values"),
          "Sets every value of a table parameter.")
      .def(
          "get",
          [](const PyParameters& p, std::size_t instance, const std::string& name) {
            return p.values.get(instance, index_of(*p.model, name));
          },
          nb::arg("instance"), nb::arg("name"), "The first value of a parameter.");
}

}  // namespace finflex::python

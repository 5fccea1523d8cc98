// finflex.RigFrame: several models (species) deformed in one frame, each entry a
// deformer with its own instances, batch and parameter rows (finflex::RigFrame).
#include <memory>
#include <string>
#include <vector>

#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "bindings.hpp"

namespace finflex::python {
namespace {

struct PyRigFrame {
  std::unique_ptr<RigFrame> frame = std::make_unique<RigFrame>();
  std::vector<nb::object> deformers;  // each entry's PyDeformer, kept alive
};

}  // namespace

void bind_frame(nb::module_& m) {
  nb::class_<PyRigFrame>(m, "RigFrame",
                         "Several models deformed in one frame: each entry a Deformer with its "
                         "own instances, batch and parameters; enqueue() launches them all "
                         "without waiting.")
      .def(nb::init<>())
      .def(
          "add",
          [](PyRigFrame& f, nb::handle_t<PyDeformer> deformer, std::size_t instances,
             const std::string& normal_format) {
            const std::size_t entry = f.frame->add(*nb::cast<PyDeformer&>(deformer).deformer,
                                                   instances, parse_normal_format(normal_format));
            f.deformers.push_back(nb::borrow(deformer));
            return entry;
          },
          nb::arg("deformer"), nb::arg("instances"), nb::arg("normal_format") = "float32",
          "Adds `instances` instances of the deformer's model (kept alive by the frame), "
          "parameters at the rest pose (zeros); returns the entry's index.")
      .def("__len__", [](const PyRigFrame& f) { return f.frame->size(); })
      .def(
          "values",
          [](nb::handle_t<PyRigFrame> self, std::size_t entry) {
            PyRigFrame& f = nb::cast<PyRigFrame&>(self);
            RigParameters& p = f.frame->parameters(entry);
            const std::size_t shape[2] = {p.instance_count(), p.values_per_instance()};
            return nb::ndarray<nb::numpy, float, nb::shape<-1, -1>>(p.values().data(), 2, shape,
                                                                    self);
          },
          nb::arg("entry"),
          "The entry's parameter rows, float32 (instances, values_per_instance), writable, "
          "without a copy: fill them each frame.")
      .def(
          "batch", [](PyRigFrame& f, std::size_t entry) { return PyBatch{f.frame->batch(entry)}; },
          nb::arg("entry"), "The entry's outputs (read them with its Deformer.read).")
      .def(
          "enqueue",
          [](PyRigFrame& f, const std::string& normals, bool clamp, const std::string& path) {
            const NormalMode mode = parse_normal_mode(normals);
            const RigPath rig_path = parse_rig_path(path);
            std::vector<cl::Event> events;
            {
              nb::gil_scoped_release release;
              events = f.frame->enqueue(mode, rig_path, clamp);
            }
            std::vector<PyEvent> out;
            out.reserve(events.size());
            for (cl::Event& e : events) out.push_back(PyEvent{std::move(e), 0.0});
            return out;
          },
          nb::arg("normals") = "rotate", nb::arg("clamp") = false, nb::arg("path") = "auto",
          "Checks every entry's parameters (nothing is enqueued on error: finflex.Error "
          "naming the value), then launches every entry; returns one Event per entry.");
}

}  // namespace finflex::python

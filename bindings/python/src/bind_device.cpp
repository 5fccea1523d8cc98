// Devices, contexts, the OpenCL deformer, its batches and events, and the CPU
// reference.
#include <cstdint>
#include <optional>

#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"
#include "job.hpp"
#include "outputs.hpp"

namespace finflex::python {
namespace {

std::uintptr_t handle_of(const cl::Buffer& buffer) {
  return reinterpret_cast<std::uintptr_t>(buffer());
}

}  // namespace

void bind_device(nb::module_& m) {
  nb::class_<DeviceDescription>(m, "Device", "An OpenCL device.")
      .def_ro("platform_index", &DeviceDescription::platform_index)
      .def_ro("device_index", &DeviceDescription::device_index)
      .def_ro("platform_name", &DeviceDescription::platform_name)
      .def_ro("device_name", &DeviceDescription::device_name)
      .def_ro("type", &DeviceDescription::type, "'GPU', 'CPU', 'accelerator' or 'other'.")
      .def_ro("version", &DeviceDescription::version)
      .def_ro("global_memory_bytes", &DeviceDescription::global_memory_bytes)
      .def_ro("max_allocation_bytes", &DeviceDescription::max_allocation_bytes)
      .def_ro("is_default", &DeviceDescription::is_default)
      .def("__repr__", [](const DeviceDescription& d) {
        return "finflex.Device('" + std::to_string(d.platform_index) + ":" +
               std::to_string(d.device_index) + "', '" + d.device_name + "', " + d.type + ")";
      });
  m.def("list_devices", &list_devices,
        "Every OpenCL device of every platform; the default is the first GPU, else the first "
        "CPU. Empty when no OpenCL platform exists.");

  nb::class_<PyContext>(m, "Context",
                        "An OpenCL device with its in-order queue and compiled programs.")
      .def(
          "__init__",
          [](PyContext* self, const std::string& device) {
            new (self) PyContext{std::make_shared<Context>(device)};
          },
          nb::arg("device") = "",
          "device: '' for the default, 'P:D' (platform, device index), or part of the "
          "device's or platform's name ('pocl', 'H100'); finflex.Error (code 'device') "
          "when nothing matches.")
      .def_prop_ro("device", [](const PyContext& c) { return c.context->description(); })
      .def(
          "finish",
          [](PyContext& c) {
            nb::gil_scoped_release release;
            check_cl(c.context->queue().finish(), "clFinish");
          },
          "Blocks until every command on the queue is done.")
      .def_prop_ro(
          "cl_context",
          [](const PyContext& c) {
            return reinterpret_cast<std::uintptr_t>(c.context->context()());
          },
          "The cl_context as an integer (e.g. pyopencl.Context.from_int_ptr); owned by this "
          "object.")
      .def_prop_ro(
          "cl_queue",
          [](const PyContext& c) { return reinterpret_cast<std::uintptr_t>(c.context->queue()()); },
          "The cl_command_queue as an integer; owned by this object.");

  nb::class_<PyEvent>(m, "Event", "The completion of a frame's work on the device.")
      .def(
          "wait",
          [](PyEvent& e) {
            nb::gil_scoped_release release;
            check_cl(e.event.wait(), "clWaitForEvents");
          },
          "Blocks until the work is done.")
      .def_prop_ro(
          "complete",
          [](const PyEvent& e) {
            cl_int status = CL_COMPLETE;
            check_cl(e.event.getInfo(CL_EVENT_COMMAND_EXECUTION_STATUS, &status), "clGetEventInfo");
            if (status < 0) check_cl(status, "the event's command");
            return status == CL_COMPLETE;
          },
          "True once the work is done (does not block).")
      .def_ro("enqueue_seconds", &PyEvent::enqueue_seconds,
              "Host time the library's enqueue took inside the call that made this event "
              "(the call's own time minus this is the Python binding's overhead).");

  nb::class_<PyBatch>(m, "Batch",
                      "Device outputs of a number of instances: positions, normals (and "
                      "tangents, previous positions) where its layout says (Batch.layout; "
                      "Deformer.allocate(n): FinFlex's planes over slots).")
      .def_prop_ro("instance_count", [](const PyBatch& b) { return b.batch.shape.instance_count; })
      .def_prop_ro("vertex_count", [](const PyBatch& b) { return b.batch.shape.vertex_count; })
      .def_prop_ro(
          "plane_stride", [](const PyBatch& b) { return b.batch.shape.plane_stride; },
          "Elements from one (instance, component) plane to the next.")
      .def_prop_ro(
          "normal_format",
          [](const PyBatch& b) { return std::string(to_string(b.batch.shape.normal_format)); })
      .def_prop_ro(
          "has_tangents", [](const PyBatch& b) { return b.batch.outputs.tangents.has_value(); },
          "Whether the batch writes tangents (its layout's tangents are set).")
      .def_prop_ro(
          "layout", [](const PyBatch& b) { return b.batch.outputs; },
          "Where each attribute is written (an OutputLayout, a copy).")
      .def(
          "cl_buffer",
          [](const PyBatch& b, const std::string& attribute) -> std::uintptr_t {
            const OutputLayout& l = b.batch.outputs;
            if (attribute == "positions") return handle_of(b.batch.positions);
            if (attribute == "normals") return handle_of(b.batch.normals);
            if (attribute == "tangents" && l.tangents) return handle_of(b.batch.tangents);
            if (attribute == "previous_positions" && l.previous_positions) {
              return handle_of(b.batch.previous_positions);
            }
            reject("attribute", "attribute = '" + attribute +
                                    "': expected 'positions', 'normals', or 'tangents' or "
                                    "'previous_positions' where the layout writes them");
          },
          nb::arg("attribute"),
          "The attribute's cl_mem as an integer (e.g. pyopencl.Buffer.from_int_ptr), owned "
          "by this batch, laid out as Batch.layout says (FinFlex's planes: element "
          "(instance i, component c, slot s) at (i * 3 + c) * plane_stride + s).");

  nb::class_<PyDeformer>(m, "Deformer",
                         "A model uploaded to a context's device: enqueues frames, each "
                         "instance with its own parameters.")
      .def(
          "__init__",
          [](PyDeformer* self, const PyContext& context, const PyModel& model) {
            new (self) PyDeformer{context.context, model.model,
                                  std::make_unique<ClDeformer>(*context.context, *model.model)};
          },
          nb::arg("context"), nb::arg("model"))
      .def(
          "allocate",
          [](const PyDeformer& d, std::size_t instances, const std::string& normal_format) {
            return PyBatch{d.deformer->allocate(instances, parse_normal_format(normal_format))};
          },
          nb::arg("instances"), nb::arg("normal_format") = "float32",
          "Device outputs for `instances` instances; normals and tangents 'float32' or "
          "'half'.")
      .def(
          "allocate",
          [](const PyDeformer& d, std::size_t instances, const OutputLayout& layout) {
            return PyBatch{d.deformer->allocate(instances, layout)};
          },
          nb::arg("instances"), nb::arg("layout"),
          "Device outputs for `instances` instances in `layout` (a buffer per attribute); "
          "finflex.Error naming the attribute ('outputs.normals.vertex_stride', ...) when "
          "the layout does not fit.")
      .def(
          "layout",
          [](const PyDeformer& d, std::size_t instances, const std::string& normal_format) {
            return d.deformer->layout(instances, parse_normal_format(normal_format));
          },
          nb::arg("instances"), nb::arg("normal_format") = "float32",
          "FinFlex's planes for `instances` instances (what allocate(instances) writes), an "
          "OutputLayout to start another from.")
      .def(
          "output_vertices",
          [](const PyDeformer& d, const std::string& order) {
            return d.deformer->output_vertices(parse_vertex_order(order));
          },
          nb::arg("order") = "slots",
          "The vertices a layout in `order` covers: 'slots' (padding included) or 'mesh'.")
      .def(
          "enqueue",
          [](nb::handle_t<PyDeformer> self, nb::handle parameters, nb::handle_t<PyBatch> batch,
             const std::string& normals, bool clamp, const std::string& path, nb::handle wait) {
            PyDeformer& d = nb::cast<PyDeformer&>(self);
            ClJob job = describe_frames(nb::cast<PyBatch&>(batch), normals, clamp, path);
            return enqueue_frame(d, job, parameters, wait);
          },
          nb::arg("parameters"), nb::arg("batch"), nb::arg("normals") = "rotate",
          nb::arg("clamp") = false, nb::arg("path") = "auto", nb::arg("wait") = nb::none(),
          nb::sig("def enqueue(self, parameters: numpy.typing.NDArray[numpy.float32] | "
                  "Parameters, batch: Batch, normals: str = 'rotate', clamp: bool = False, path: "
                  "str = 'auto', wait: collections.abc.Sequence[Event] | None = None) -> Event"),
          "Checks the parameters against the rig's limits (finflex.Error naming e.g. 'm[3]' "
          "and the value; nothing is enqueued on error), uploads them and enqueues the "
          "kernels after the `wait` events. Returns without waiting: the frame's event.\n"
          "parameters: float32 (instances, values_per_instance) with contiguous rows (not "
          "copied), or a finflex.Parameters; normals: 'rotate' (the paper's (8)) or "
          "'jacobian' (exact); clamp: clamp values into their range instead of an error; "
          "path: 'auto', 'fused' or 'passes'.")
      .def(
          "job",
          [](nb::handle_t<PyDeformer> self, nb::handle_t<PyBatch> batch, const std::string& normals,
             bool clamp, const std::string& path) {
            return PyJob{nb::borrow(self), nb::borrow(batch),
                         describe_frames(nb::cast<PyBatch&>(batch), normals, clamp, path)};
          },
          nb::arg("batch"), nb::arg("normals") = "rotate", nb::arg("clamp") = false,
          nb::arg("path") = "auto",
          "A Job into `batch` with these settings, for a frame loop: job.enqueue(parameters) "
          "is enqueue() with the least work per call.")
      .def(
          "read",
          [](PyDeformer& d, const PyBatch& batch) {
            DeformedBatch<float> read;
            {
              nb::gil_scoped_release release;
              read = d.deformer->read(batch.batch);
            }
            return Outputs(std::move(read), d.model);
          },
          nb::arg("batch"),
          "Blocking copy of the batch to the host: Outputs with float32 (instances, "
          "vertices, 3) arrays in mesh vertex order.")
      .def(
          "save_instance",
          [](PyDeformer& d, const PyBatch& batch, std::size_t instance, const std::string& path) {
            save_mesh(path,
                      instance_mesh(d.model->mesh(), d.deformer->read(batch.batch), instance));
          },
          nb::arg("batch"), nb::arg("instance"), nb::arg("path"),
          "Blocking: writes one instance of the batch as a mesh file.")
      .def_prop_ro(
          "slot_of_vertex", [](const PyDeformer& d) { return d.deformer->slot_of_vertex(); },
          "Each mesh vertex's slot in the device planes.")
      .def_prop_ro(
          "remapped_indices", [](const PyDeformer& d) { return d.deformer->remapped_indices(); },
          "The mesh's triangles over slots: draw the device buffers with them.")
      .def_prop_ro("uses_single_bend_kernel",
                   [](const PyDeformer& d) { return d.deformer->uses_single_bend_kernel(); });

  m.def(
      "deform_reference",
      [](const PyModel& model, nb::handle parameters, const std::string& normals, bool clamp) {
        const ParameterArgument rows(parameters, *model.model);
        DeformedBatch<double> out;
        ReferenceJob job;
        job.instances = rows.view().instance_count;
        job.parameters = rows.view();
        job.normals = parse_normal_mode(normals);
        job.clamp = clamp;
        job.outputs = &out;
        {
          nb::gil_scoped_release release;
          run_reference(*model.model, job);
        }
        return Outputs(std::move(out), model.model);
      },
      nb::arg("model"), nb::arg("parameters"), nb::arg("normals") = "rotate",
      nb::arg("clamp") = false,
      nb::sig("def deform_reference(model: Model, parameters: "
              "numpy.typing.NDArray[numpy.float32] | Parameters, normals: str = 'rotate', clamp: "
              "bool = False) -> Outputs"),
      "The CPU reference (double precision, the tests' oracle) of the same job: Outputs "
      "with float64 (instances, vertices, 3) arrays in mesh vertex order.");
}

}  // namespace finflex::python

// Swimming fish from Python (finflex/swim.hpp, finflex/cl_swim.hpp): SwimModel (a swim
// rig made ready to swim), SwimDriver (the driver kernel: each frame every fish's pose,
// speed and turning rate in, its rig parameters and world placement written on the
// device) and SwimJob (a deformer's frames reading them: outputs in world space).
#include <optional>
#include <vector>

#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "arrays.hpp"
#include "job.hpp"

namespace finflex::python {
namespace {

struct PySwimModel {
  std::shared_ptr<const SwimModel> swim;
};

struct PySwimDriver {
  std::shared_ptr<Context> context;
  std::shared_ptr<const SwimModel> swim;
  std::unique_ptr<ClSwimDriver> driver;
  std::vector<float> rows;  // the frame's inputs when copied (not C-ordered), reused
};

// A frame's device work held back until all of it is enqueued (finflex::FrameGate).
struct PyFrameGate {
  std::shared_ptr<Context> context;  // outlives the gate
  std::unique_ptr<FrameGate> gate;
};

// A deformer's frames whose parameters and placements are a driver's device buffers.
struct PySwimJob {
  nb::object deformer, batch, driver;  // kept alive
  ClJob job;
};

// A float32 numpy array that owns `values`, of the given shape.
nb::ndarray<nb::numpy, float> owned_array(std::vector<float> values,
                                          std::initializer_list<std::size_t> shape) {
  auto* held = new std::vector<float>(std::move(values));
  nb::capsule owner(held, [](void* p) noexcept { delete static_cast<std::vector<float>*>(p); });
  return nb::ndarray<nb::numpy, float>(held->data(), shape.size(), shape.begin(), owner);
}

// The deformer's model as the swim model's own (SwimModel holds a copy of the model
// it was made from): an aliasing pointer that keeps the swim model alive.
std::shared_ptr<const RiggedMesh> model_of(const std::shared_ptr<const SwimModel>& swim) {
  return std::shared_ptr<const RiggedMesh>(swim, &swim->model());
}

}  // namespace

void bind_swim(nb::module_& m) {
  nb::class_<PySwimModel>(m, "SwimModel",
                          "A swim rig made ready to swim (finflex/swim.hpp): a spine "
                          "'body_wave' on the root, optional fin hinges 'tail_angle', "
                          "'right_pectoral_angle', 'left_pectoral_angle'. Make the "
                          "Deformer from its .model.")
      .def(
          "__init__",
          [](PySwimModel* self, const PyModel& model) {
            new (self) PySwimModel{std::make_shared<const SwimModel>(*model.model)};
          },
          nb::arg("model"),
          "finflex.Error (field 'swim.wave') when the rig has no spine on its body.")
      .def_prop_ro(
          "model", [](const PySwimModel& s) { return PyModel{model_of(s.swim)}; },
          "The swim model's own Model: the one a Deformer for its SwimJobs is made from.")
      .def_prop_ro(
          "samples", [](const PySwimModel& s) { return s.swim->samples(); },
          "Angles in the spine's table.");

  nb::class_<PySwimDriver>(m, "SwimDriver",
                           "The swim driver on a context's device (finflex/cl_swim.hpp): "
                           "per fish its phases (device state), rig parameters and world "
                           "placement.")
      .def(
          "__init__",
          [](PySwimDriver* self, const PyContext& context, const PySwimModel& swim,
             const std::vector<float>& lengths, const std::optional<std::vector<float>>& phases) {
            new (self)
                PySwimDriver{context.context,
                             swim.swim,
                             std::make_unique<ClSwimDriver>(*context.context, *swim.swim, lengths,
                                                            phases.value_or(std::vector<float>{})),
                             {}};
          },
          nb::arg("context"), nb::arg("swim"), nb::arg("lengths"), nb::arg("phases") = nb::none(),
          "One fish per length (metres, > 0); phases (cycles) per fish or 0. finflex.Error "
          "naming 'lengths[i]' or 'phases'.")
      .def_prop_ro("fish_count", [](const PySwimDriver& d) { return d.driver->fish_count(); })
      .def(
          "enqueue",
          [](PySwimDriver& d, nb::handle inputs, float dt, nb::handle wait) {
            // C-ordered rows are read where they are; others are copied first.
            std::size_t count = 0;
            const float* rows = float_rows_in_place(inputs, "inputs", 7, d.rows, count);
            const std::size_t fish = d.driver->fish_count();
            // A wrong count is named before anything is staged; the rows go straight
            // into the upload's staging memory (holding the GIL while the array is
            // read), checked there with dt.
            if (count != fish) check_swim_inputs(nullptr, count, fish, dt);
            const std::vector<cl::Event> events = wait_events(wait);
            swim_inputs_from_rows(rows, count, d.driver->staged_inputs());
            PyEvent done;
            nb::gil_scoped_release release;
            done.event = d.driver->enqueue_staged(dt, events.empty() ? nullptr : &events);
            return done;
          },
          nb::arg("inputs"), nb::arg("dt"), nb::arg("wait") = nb::none(),
          nb::sig("def enqueue(self, inputs: numpy.typing.NDArray[numpy.float32], dt: float, "
                  "wait: collections.abc.Sequence[Event] | None = None) -> Event"),
          "One frame of dt seconds: inputs float32 (fish, 7), per fish x, y, z (the pivot, "
          "m, y up), yaw (about +y, 0 towards +x), pitch, speed (m/s, >= 0), turning rate "
          "(rad/s, > 0 to the fish's left). finflex.Error naming 'inputs[i].speed' etc.; "
          "nothing is enqueued on error. Returns the driver kernel's event.")
      .def(
          "read_parameters",
          [](PySwimDriver& d) {
            const RigParameters values = d.driver->read_parameters();
            return owned_array(values.values(),
                               {d.driver->fish_count(), values.values_per_instance()});
          },
          "Blocking: the rig parameters the last frame wrote, float32 (fish, values).")
      .def(
          "read_wave_phases",
          [](PySwimDriver& d) {
            return owned_array(d.driver->read_wave_phases(), {d.driver->fish_count()});
          },
          "Blocking: each fish's body-wave phase (cycles, in [0, 1)).")
      .def(
          "read_placements",
          [](PySwimDriver& d) {
            std::vector<float> flat;
            for (const PlacementRecord& record : d.driver->read_placements())
              flat.insert(flat.end(), record.begin(), record.end());
            return owned_array(std::move(flat), {d.driver->fish_count(), kPlacementFloats});
          },
          "Blocking: each fish's placement record (finflex/placement.hpp: the columns of "
          "L Q, the position, 1 / L), float32 (fish, 16).")
      .def(
          "limited_segments", [](PySwimDriver& d) { return d.driver->read_limited_segments(); },
          "Blocking: spine segments the last frame bent less than asked, to clear folding.");

  nb::class_<PySwimJob>(m, "SwimJob",
                        "A deformer's frames into one batch from a SwimDriver's device "
                        "buffers (Deformer.swim_job): outputs in world space.")
      .def(
          "enqueue",
          [](PySwimJob& j, nb::handle wait) {
            return enqueue_job(nb::cast<PyDeformer&>(j.deformer), j.job, wait);
          },
          nb::arg("wait") = nb::none(),
          nb::sig("def enqueue(self, wait: collections.abc.Sequence[Event] | None = None) -> "
                  "Event"),
          "The deformation of the driver's last frame (enqueue it after driver.enqueue: "
          "the queue is in order).")
      .def_prop_ro(
          "batch",
          [](const PySwimJob& j) -> const PyBatch& { return nb::cast<const PyBatch&>(j.batch); },
          nb::rv_policy::reference_internal, "The batch the job writes.");

  nb::class_<PyFrameGate>(
      m, "FrameGate",
      "Holds a frame's device work back until all of it is enqueued: pass [gate.event] "
      "as the wait list of the frame's first command (driver.enqueue(..., wait=...)), "
      "enqueue the rest, then gate.open() (or use it as a context manager, which opens "
      "it on leaving). On NVIDIA's OpenCL the frame then goes to the device whole. "
      "Nothing may wait for the device (Event.wait(), a read) while it is closed.")
      .def(
          "__init__",
          [](PyFrameGate* self, const PyContext& context) {
            new (self) PyFrameGate{context.context, std::make_unique<FrameGate>(*context.context)};
          },
          nb::arg("context"))
      .def_prop_ro(
          "event",
          [](const PyFrameGate& g) {
            PyEvent event;
            event.event = g.gate->wait_list()->front();
            return event;
          },
          "The gate's event, complete once it is open.")
      .def(
          "open", [](PyFrameGate& g) { g.gate->open(); },
          "Lets the work behind the gate run (again: nothing).")
      .def_prop_ro("is_open", [](const PyFrameGate& g) { return g.gate->is_open(); })
      .def("__enter__", [](nb::handle self) { return nb::borrow(self); })
      .def(
          "__exit__",
          [](PyFrameGate& g, nb::handle, nb::handle, nb::handle) {
            g.gate->open();
            return false;
          },
          nb::arg("type").none(), nb::arg("value").none(), nb::arg("traceback").none());

  // Deformer.swim_job (the Deformer class is bound before this file's classes).
  nb::handle deformer_class = m.attr("Deformer");
  deformer_class.attr("swim_job") = nb::cpp_function(
      [](nb::handle_t<PyDeformer> self, nb::handle_t<PyBatch> batch,
         nb::handle_t<PySwimDriver> driver, const std::string& normals, const std::string& path) {
        const PyDeformer& d = nb::cast<const PyDeformer&>(self);
        const PySwimDriver& swim = nb::cast<const PySwimDriver&>(driver);
        if (&swim.swim->model() != d.model.get()) {
          reject("driver",
                 "driver: its SwimModel's model is not the deformer's (make the "
                 "Deformer from swim_model.model)");
        }
        PySwimJob job{nb::borrow(self), nb::borrow(batch), nb::borrow(driver),
                      describe_frames(nb::cast<PyBatch&>(batch), normals, false, path)};
        job.job.instances = swim.driver->fish_count();
        job.job.device.parameters = &swim.driver->parameter_buffer();
        job.job.device.placements = &swim.driver->placement_buffer();
        job.job.device.derived = swim.driver->derived_buffer();
        return job;
      },
      nb::is_method(), nb::scope(deformer_class), nb::name("swim_job"), nb::arg("batch"),
      nb::arg("driver"), nb::arg("normals") = "rotate", nb::arg("path") = "auto",
      "A SwimJob into `batch` (at least driver.fish_count instances) reading the driver's "
      "parameters and placements on the device: job.enqueue() after driver.enqueue(...) "
      "each frame. The deformer must be made from the SwimModel's .model.");
}

}  // namespace finflex::python

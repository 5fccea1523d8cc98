// The deformation job: one description that both backends run, the double-precision
// CPU reference (finflex/reference.hpp, ReferenceJob) and the OpenCL backend
// (finflex/cl_deformer.hpp, ClJob). They differ only in where the outputs go and in
// what they can wait for:
//
//   ReferenceJob job;                      ClJob job;
//   job.model = &fish;                     job.model = &fish;
//   job.parameters = values.view();        job.parameters = values.view();
//   job.normals = NormalMode::kJacobian;   job.normals = NormalMode::kJacobian;
//   job.outputs = &host_batch;             job.outputs = &device_batch;
//   run_reference(job);                    cl::Event done = deformer.enqueue(job);
//
// validate() checks the fields every backend needs and names the one at fault; each
// backend runs it first, then its own checks (its outputs, its model).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "finflex/export.hpp"
#include "finflex/model.hpp"
#include "finflex/parameters.hpp"
#include "finflex/placement.hpp"

namespace finflex {

enum class NormalMode {
  kRotate,    // the paper's (8): rotate by R, the rotation taking e_z to the secant normal
  kJacobian,  // exact: transform by the cofactor of the deformation's Jacobian (METHOD.md 6)
};
FINFLEX_API const char* to_string(NormalMode mode);
// Parses "rotate" / "jacobian"; errors name `field` and the value.
FINFLEX_API NormalMode parse_normal_mode(const std::string& text,
                                         const std::string& field = "normals");

// How the OpenCL backend runs a rig (the reference applies the stages one by one
// whatever it says).
enum class RigPath {
  kAuto,    // fused where it applies (every path of at most kMaxFusedStages stages)
  kFused,   // one pass: each vertex applies its whole bottom-up path in registers
  kPasses,  // one pass per (hierarchy level, chain position), ping-pong buffers, as the
            // paper's stream-out; a pass touches only the vertices it has a stage for
};
FINFLEX_API const char* to_string(RigPath path);
FINFLEX_API RigPath parse_rig_path(const std::string& text, const std::string& field = "path");

// The event and buffer types of a backend that runs at once on host memory (the CPU
// reference).
struct NoEvent {};
struct NoBuffer {};

template <typename Outputs, typename Event, typename Buffer>
struct BasicDeformJob {
  // ---- Job input ----
  // The rest mesh and its rig.
  const RiggedMesh* model = nullptr;
  // Per instance, the rig's parameter values (RigParameters::view()); the job
  // deforms parameters.instance_count instances.
  ParameterView parameters;
  NormalMode normals = NormalMode::kRotate;
  // Out-of-range values: an error (false), or clamped into their range (true).
  bool clamp = false;
  RigPath path = RigPath::kAuto;
  // Optional world placement, one per instance (finflex/placement.hpp): outputs in
  // world space. Null: mesh coordinates.
  const Placement* placements = nullptr;

  // ---- Job input already on the device (OpenCL) ----
  // Written by a kernel of the caller's (e.g. a swim driver, finflex/swim.hpp) and used
  // instead of uploading: `parameter_buffer` instead of parameters.data (rows of
  // values_per_instance() floats, packed; parameters.instance_count still counts the
  // instances; the values are the writer's to keep in range, nothing checks them on
  // the host), `placement_buffer` instead of `placements` (kPlacementFloats per
  // instance). Null: none.
  const Buffer* parameter_buffer = nullptr;
  const Buffer* placement_buffer = nullptr;
  // The rig's derived values of this frame (DeformerType::derived_count: a spine's
  // running integrals), already written by the kernel that wrote parameter_buffer
  // (ClSwimDriver::derived_buffer()), in the layout rig_prepare writes
  // (ClDeformer::derived_floats_per_instance() floats per instance): the frame skips
  // rig_prepare. Null: rig_prepare computes them from the parameters.
  const Buffer* derived_buffer = nullptr;

  // ---- Job output ----
  // Where the deformed positions, normals and tangents go (the backend's kind).
  Outputs* outputs = nullptr;

  // ---- Ordering ----
  // Work the job's first command waits for (OpenCL events); none when null.
  const std::vector<Event>* wait = nullptr;

  // Throws kInvalidArgument naming the field ("job.model", "job.outputs",
  // "job.parameters.data", "job.parameters.instance_count",
  // "job.parameters.stride", "job.placements") when one is missing or inconsistent.
  // Values are checked by the backends (check_parameters), which name the value at
  // fault.
  void validate() const {
    if (model == nullptr) fail("job.model", "job.model is null: the job needs a model");
    if (outputs == nullptr) fail("job.outputs", "job.outputs is null: the job needs outputs");
    if (parameters.instance_count == 0) {
      fail("job.parameters.instance_count",
           "job.parameters.instance_count = 0: at least one instance is needed");
    }
    if (placements != nullptr && placement_buffer != nullptr) {
      fail("job.placements", "job.placements and job.placement_buffer are both set: give one");
    }
    const std::size_t values = model->values_per_instance();
    if (parameter_buffer != nullptr) return;  // values on the device
    if (parameters.data == nullptr && values > 0) {
      fail("job.parameters.data", "job.parameters.data is null: the model's rig reads " +
                                      std::to_string(values) + " values per instance");
    }
    if (parameters.stride != 0 && parameters.stride < values) {
      fail("job.parameters.stride", "job.parameters.stride = " + std::to_string(parameters.stride) +
                                        " is below the model's " + std::to_string(values) +
                                        " values per instance");
    }
  }

 private:
  [[noreturn]] static void fail(const char* field, const std::string& message) {
    throw Error(ErrorCode::kInvalidArgument, field, message);
  }
};

}  // namespace finflex

// A frame's job: what both backends deform, the double-precision CPU reference
// (finflex/reference.hpp, ReferenceJob) and the OpenCL backend (finflex/cl_deformer.hpp,
// ClJob). It names only what varies per frame; the model is the backend's
// (ClDeformer's own, or run_reference's argument):
//
//   ReferenceJob job;                      ClJob job;
//   job.instances = 4000;                  job.instances = 4000;
//   job.parameters = values.view();        job.parameters = values.view();
//   job.normals = NormalMode::kJacobian;   job.normals = NormalMode::kJacobian;
//   job.outputs = &host_batch;             job.outputs = &device_batch;
//   run_reference(fish, job);              cl::Event done = deformer.enqueue(job);
//
// validate() checks the fields every backend needs and names the one at fault; each
// backend runs it first, then its own checks (its outputs).
#pragma once

#include <cstddef>
#include <string>

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

// How the OpenCL backend runs a rig (the reference applies the stages one by one).
enum class RigPath {
  kAuto,    // fused where it applies (every path of at most kMaxFusedStages stages)
  kFused,   // one pass: each vertex applies its whole bottom-up path in registers
  kPasses,  // one pass per (hierarchy level, chain position), ping-pong buffers, as the
            // paper's stream-out; a pass touches only the vertices it has a stage for
};
FINFLEX_API const char* to_string(RigPath path);
FINFLEX_API RigPath parse_rig_path(const std::string& text, const std::string& field = "path");

template <typename Outputs>
struct BasicDeformJob {
  // Instances to deform: the outputs hold exactly this many.
  std::size_t instances = 0;
  // Their parameter values (RigParameters::view()): at least `instances` rows of the
  // model's values_per_instance() floats. Row i is instance i.
  ParameterView parameters;
  // Optional world placement, one per instance (finflex/placement.hpp): outputs in
  // world space. Null: mesh coordinates.
  const Placement* placements = nullptr;
  NormalMode normals = NormalMode::kRotate;
  // Out-of-range values: an error (false), or clamped into their range (true).
  bool clamp = false;
  // Where the deformed positions, normals and tangents go (the backend's kind).
  Outputs* outputs = nullptr;

  // Throws kInvalidArgument naming the field ("job.instances", "job.outputs",
  // "job.parameters.data", "job.parameters.instance_count", "job.parameters.stride")
  // when one is missing or inconsistent with `model`; `values_on_device`: the values
  // come from a device buffer instead of `parameters`. Values are checked by the
  // backends (check_parameters), which name the value at fault.
  void validate(const RiggedMesh& model, bool values_on_device = false) const {
    if (outputs == nullptr) fail("job.outputs", "job.outputs is null: the job needs outputs");
    if (instances == 0) {
      fail("job.instances", "job.instances = 0: at least one instance is needed");
    }
    const std::size_t values = model.values_per_instance();
    if (values_on_device || values == 0) return;
    if (parameters.data == nullptr) {
      fail("job.parameters.data", "job.parameters.data is null: the model's rig reads " +
                                      std::to_string(values) + " values per instance");
    }
    if (parameters.instance_count < instances) {
      fail("job.parameters.instance_count",
           "job.parameters.instance_count = " + std::to_string(parameters.instance_count) +
               " rows of values for job.instances = " + std::to_string(instances));
    }
    if (parameters.stride != 0 && parameters.stride < values) {
      fail("job.parameters.stride", "job.parameters.stride = " + std::to_string(parameters.stride) +
                                        " is below the model's " + std::to_string(values) +
                                        " values per instance");
    }
  }
  // The rows of `parameters` this job deforms (its first `instances`).
  ParameterView rows() const { return {parameters.data, instances, parameters.stride}; }

 private:
  [[noreturn]] static void fail(const char* field, const std::string& message) {
    throw Error(ErrorCode::kInvalidArgument, field, message);
  }
};

}  // namespace finflex

// The CPU reference backend: a job's stages applied literally, vertex by vertex, in
// double precision (METHOD.md sections 2-6): for every vertex, its component's chain,
// then its parent's, ... up to the root's; each stage goes into its frame by (2),
// moves the vertex by (7) on its deformer's secant surface, turns the normal by (8) or
// by the Jacobian's cofactor, and goes back out by (2). The tests' oracle; it needs no
// OpenCL.
//
//   ReferenceJob job;
//   job.instances = values.instance_count();
//   job.parameters = values.view();
//   DeformedBatch<double> out;
//   job.outputs = &out;
//   run_reference(fish, job);
//
// Thread-safety: run_reference only reads the model and the parameters; jobs may run
// on several threads at once, each with its own outputs.
#pragma once

#include <glm/glm.hpp>

#include "finflex/batch.hpp"
#include "finflex/deformer_type.hpp"
#include "finflex/export.hpp"
#include "finflex/job.hpp"

namespace finflex {

using ReferenceJob = BasicDeformJob<DeformedBatch<double>>;

// Validates the job against `model` (ReferenceJob::validate), checks the parameters
// (check_parameters), then deforms every instance of `model` into *job.outputs,
// resized to the model's vertices in the mesh's own order (plane_stride
// padded_plane_stride of the vertex count), placed in the world when job.placements is
// given. On error the outputs are left as they were.
FINFLEX_API void run_reference(const RiggedMesh& model, const ReferenceJob& job);

// The same for a whole RigParameters (with world `placements`, one per instance, or
// none): a convenience for tests and tools.
FINFLEX_API DeformedBatch<double> run_reference(const RiggedMesh& model,
                                                const RigParameters& parameters, NormalMode normals,
                                                bool clamp = false,
                                                const Placement* placements = nullptr);

// One vertex in a stage's frame: position, unit normal, unit tangent (zero when the
// mesh has none).
struct LocalVertex {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};
  glm::dvec3 tangent{0.0};
};

// One stage of `deformer` (with `options`, the stage's `values` and the geometry of its
// vertices, which some deformers need: a spine's table spans their x extent) on a
// vertex in the stage's frame, as the reference applies it: the deformer's secant surface at x, the
// position by (7), the normal by (8) (the Rodrigues rotation taking e_z to the surface
// normal) or by the Jacobian's cofactor, the tangent by R or by J.
FINFLEX_API LocalVertex apply_stage(const DeformerType& deformer, const StageOptions& options,
                                    const double* values, const LocalVertex& rest,
                                    NormalMode normals, const StageGeometry& geometry = {});

}  // namespace finflex

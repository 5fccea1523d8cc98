// One vertex through its component's path of stages, in double precision: the CPU
// reference's core (METHOD.md section 2), also used by the accuracy checks to learn
// how well conditioned each vertex's stages are.
#pragma once

#include <cstddef>

#include "finflex/job.hpp"
#include "finflex/model.hpp"
#include "reference/secant_surface.hpp"

namespace finflex::detail {

// What a vertex met along its path.
struct PathConditioning {
  std::size_t stages = 0;     // stages on its path
  bool near_limit = false;    // a stage near its range limit (SecantSample::near_limit)
  double near_limit_z = 0.0;  // the largest |z| s_x (mesh units) at such a stage
  bool near_fold = false;     // |1 - z k| < kFoldMargin at a stage: ill-defined normals
  bool folded = false;        // z k >= 1 at a stage: past the fold-over
};

// |1 - z k| below this: on or near a fold (finflex/accuracy.hpp).
constexpr double kFoldMargin = 0.05;

// The rest vertex v of the model's mesh: position, unit normal, unit tangent (zero
// without tangents).
Vertex rest_vertex(const Mesh& mesh, std::size_t v);

// Vertex v of `model` through its path, bottom-up, with one instance's parameter row
// (`row`, values_per_instance() values, as doubles); mesh coordinates in and out.
Vertex deform_vertex(const RiggedMesh& model, std::size_t v, const double* row, NormalMode normals,
                     PathConditioning* conditioning = nullptr);

}  // namespace finflex::detail

// Accuracy diagnostics: an OpenCL batch against the double reference, with bounds
// that follow the conditioning of each vertex's stages, and geometric checks of a
// deformed mesh. Used by the tests, by `finflex check`, and by anyone validating a new
// device or driver.
//
// Bounds (docs/accuracy.md says why), per vertex, times the number of stages on its
// path (every stage adds its own float32 rounding):
//  - positions: 4e-6 (|origin| + s_x) in mesh units, origin and s_x of the root's
//    frame: a few float32 ulps of the largest coordinate the kernels handle;
//  - normals and tangents: 2e-5 (|difference| of unit vectors);
//  - where a stage is near its range limit (SecantSample::near_limit: the exact bend
//    with 1 - (2mx)^2 < 1e-3, whose slope sqrt(1 - 4m^2x^2) has an infinite
//    derivative, so the float rounding of x alone moves the secant normal by up to
//    ~5e-4): normals get 2e-3, positions 2e-3 |z| s_x more (s_x of that stage);
//  - Jacobian normals on or near a fold (|1 - z k| < 0.05 at a stage, METHOD.md
//    section 6) or near a range limit are ill-defined: counted as skipped, not compared.
#pragma once

#include <cstddef>

#include "finflex/batch.hpp"
#include "finflex/export.hpp"
#include "finflex/job.hpp"
#include "finflex/mesh.hpp"
#include "finflex/model.hpp"
#include "finflex/parameters.hpp"

namespace finflex {

struct AccuracyReport {
  double max_position_error = 0.0;  // mesh units
  double max_normal_error = 0.0;    // over the compared normals and tangents
  double max_position_ratio = 0.0;  // error / bound; <= 1 is within tolerance
  double max_normal_ratio = 0.0;
  std::size_t compared = 0;         // vertex instances whose normals were compared
  std::size_t skipped_normals = 0;  // ill-defined Jacobian normals, not compared

  bool within_tolerance() const { return max_position_ratio <= 1.0 && max_normal_ratio <= 1.0; }
};

// Compares `device` with `reference`, both deformations of `model` with `parameters`
// (already checked or clamped: the values the backends used) and `normals`, placed
// with `placements` when given (one per instance: the position bounds then scale with
// |position| + length in world units instead of the root frame's). Throws
// kInvalidArgument when the batches do not match the model and the instance count.
FINFLEX_API AccuracyReport compare_to_reference(const RiggedMesh& model,
                                                const ParameterView& parameters, NormalMode normals,
                                                const DeformedBatch<float>& device,
                                                const DeformedBatch<double>& reference,
                                                const Placement* placements = nullptr);

// Mean angle (radians) between the mesh's vertex normals and the area-weighted normals
// of its own faces: how well normals agree with the surface they shade.
FINFLEX_API double mean_angle_to_face_normals(const Mesh& mesh);

// Vertices of `instance` past the fold-over of a stage on their path (z k >= 1 in the
// stage's frame: farther from the spine than its radius of curvature, on the inside
// of the bend). There the deformed surface passes through itself; a property of the
// mesh and the parameters.
FINFLEX_API std::size_t count_folded_vertices(const RiggedMesh& model,
                                              const ParameterView& parameters,
                                              std::size_t instance);

}  // namespace finflex

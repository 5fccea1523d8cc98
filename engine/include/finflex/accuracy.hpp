// Accuracy diagnostics: a device batch against the double reference, with bounds that
// follow the conditioning of the bend, and geometric checks of a deformed mesh. Used
// by the tests, by `finflex check`, and by anyone validating a new device or driver.
//
// Bounds (docs/accuracy.md says why):
//  - positions: 4e-6 (|origin| + s_x) in mesh units: a few float32 ulps of the largest
//    coordinate the kernels handle;
//  - normals and tangents: 2e-5 (|difference| of unit vectors);
//  - near the exact bend's range limit (1 - (2mx)^2 < 1e-3) the slope sqrt(1 - 4m^2x^2)
//    has an infinite derivative and the float rounding of x alone moves the secant
//    normal by up to ~5e-4: normals get 2e-3, positions 2e-3 |z| s_x more;
//  - Jacobian normals on or near a fold (|1 - z k| < 0.05, METHOD.md section 6) or near
//    the exact limit (k = 2m / sqrt(1 - u^2) -> infinity) are ill-defined: counted as
//    skipped, not compared.
#pragma once

#include <cstddef>
#include <vector>

#include "finflex/batch.hpp"
#include "finflex/bend.hpp"
#include "finflex/local_mesh.hpp"
#include "finflex/mesh.hpp"

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

// Compares `device` with `reference`, both made from `local` with parameters `m` and
// `settings`. Throws kInvalidArgument when the layouts do not match.
AccuracyReport compare_to_reference(const LocalMesh& local, const std::vector<float>& m,
                                    const BendSettings& settings,
                                    const DeformedBatch<float>& device,
                                    const DeformedBatch<double>& reference);

// Mean angle (radians) between the mesh's vertex normals and the area-weighted normals
// of its own faces: how well normals agree with the surface they shade.
double mean_angle_to_face_normals(const Mesh& mesh);

// Vertices past the fold-over of the offset surface for bend parameter m (z k >= 1:
// farther from the spine than its radius of curvature, on the inside of the bend).
// There the deformed surface passes through itself; a property of the mesh and m.
std::size_t count_folded_vertices(const LocalMesh& local, double m, BendMode mode);

}  // namespace finflex

// The CPU reference backend: the bend applied literally, formula by formula, in double
// precision. Same interface as ClDeformer; the tests use it as the oracle.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "finflex/batch.hpp"
#include "finflex/bend.hpp"
#include "finflex/local_mesh.hpp"

namespace finflex {

// One vertex in the body frame before and after the bend.
struct LocalVertex {
  glm::dvec3 position;
  glm::dvec3 normal;
  glm::dvec3 tangent;  // ignored / zero when the mesh has no tangents
};

// The bend of one vertex in the body frame, literally as METHOD.md writes it:
// position by (7) with f from (16) (paper) or the closed form (exact); the secant
// normal n from (17) or its exact counterpart; normals by (8) with R the Rodrigues
// rotation taking e_z to n, or by the cofactor of the Jacobian J = [dp'/dx dp'/dy dp'/dz];
// tangents by R or by J.
LocalVertex bend_local_vertex(const LocalVertex& rest, double m, const BendSettings& settings);

class ReferenceDeformer {
 public:
  explicit ReferenceDeformer(const LocalMesh& mesh) : mesh_(mesh) {}

  const LocalMesh& mesh() const { return mesh_; }
  BatchLayout layout(std::size_t instances) const;

  // Deforms one instance per entry of m (checked by checked_bend_params) and returns
  // positions, normals and tangents in mesh coordinates.
  DeformedBatch<double> run(const std::vector<float>& m, const BendSettings& settings,
                            bool clamp = false) const;

 private:
  LocalMesh mesh_;
};

}  // namespace finflex

// A rest mesh expressed in its body frame (METHOD.md (2)): what every deformer reads.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/body_frame.hpp"
#include "finflex/mesh.hpp"

namespace finflex {

struct LocalMesh {
  BodyFrame frame;                     // local <-> mesh coordinates
  std::vector<glm::dvec3> positions;   // p = M p_b
  std::vector<glm::dvec3> normals;     // n = R_b n_b, unit
  std::vector<glm::dvec4> tangents;    // xyz = R_b t_b (unit), w = bitangent sign; may be empty
  std::vector<std::uint32_t> indices;  // the mesh's triangles, unchanged
  double x_max = 0.0;                  // largest |x|: sets the valid range of m (13)

  std::size_t vertex_count() const { return positions.size(); }
  bool has_tangents() const { return !tangents.empty(); }
};

// Validates `mesh` and `frame`, then expresses the mesh in the frame. Normals and
// tangents are re-normalised. Throws kInvalidMesh when the mesh has no extent along
// the spine (x_max == 0).
LocalMesh make_local_mesh(const Mesh& mesh, const BodyFrame& frame);

}  // namespace finflex

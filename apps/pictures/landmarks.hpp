// The two points a fish is measured between: the tip of the snout and the fork of the
// tail (fork length, the length fisheries measure). Both are vertices of the rest
// mesh, so their deformed positions come straight from the engine's output.
#pragma once

#include <cstdint>

#include "finflex/model.hpp"

namespace finflex::pictures {

struct FishLandmarks {
  std::uint32_t snout = 0;      // mesh vertex index
  std::uint32_t tail_fork = 0;  // mesh vertex index
  // (x_snout - x_fork) / s_x: the fork length as a fraction of the total length (the
  // body frame's s_x, the length a placement scales to), straight rest pose.
  double fork_fraction = 1.0;
};

// In the rig root's frame (e_x towards the head, e_y dorsal, lengths in body lengths):
//   snout: the vertex farthest forward (largest x);
//   tail fork: among the rearmost fifth of the body (x < x_min + 0.2), the vertices
//     within 5 % of the body length of the tail's mid-height (the middle of the
//     rearmost tenth's y range), the rearmost one: where the trailing edge of the
//     caudal fin crosses its middle, the fork's notch on a forked tail and the tip on
//     a round one.
FishLandmarks find_landmarks(const RiggedMesh& model);

}  // namespace finflex::pictures

// The mesh the rig fuzzers resolve against: a small synthetic fish (82 vertices) with
// two face groups, "head" and "tail", so group selectors can match.
#pragma once

#include "finflex/mesh.hpp"
#include "finflex/rig.hpp"

namespace finflex::fuzz {

const Mesh& rig_fuzz_mesh();

// Resolves nothing new: the model of `rig` on rig_fuzz_mesh(), and one reference frame
// of it (two instances at -0.5 and 0.7 of every parameter's limit). Errors
// (finflex::Error) are expected results; any other exception or a crash is a finding.
void exercise(const Rig& rig);

}  // namespace finflex::fuzz

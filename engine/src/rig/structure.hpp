// The structure every consumer of a Rig relies on, checked once when a model is made
// (RiggedMesh): resolve_rig's rigs have it by construction, a rig put together in code
// may not.
#pragma once

#include "finflex/rig.hpp"

namespace finflex::detail {

// Throws kInvalidArgument (field "rig", "rig: <where>: <problem>") unless: parents
// come before their children (the root first, alone), the nesting and the paths are
// within kMaxRigDepth and kMaxRigPathStages, subtree_end matches the tree, every stage
// has a deformer and reads a parameter of the rig with as many values as it takes, and
// every parameter lies inside values_per_instance(). O(components + stages).
void check_rig_structure(const Rig& rig);

}  // namespace finflex::detail

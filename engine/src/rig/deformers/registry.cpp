// The deformer registry: every deformer kind FinFlex knows, one line each. A new
// deformer adds its line here (and its files: engine/src/rig/deformers/<name>.cpp,
// kernels/deformers/<name>.cl).
#include "finflex/deformer_type.hpp"

namespace finflex {
namespace deformers {

const DeformerType& bend();   // deformers/bend.cpp: the paper's fish bend (12)-(17)
const DeformerType& hinge();  // deformers/hinge.cpp: a fin folding about its base
const DeformerType& spine();  // deformers/spine.cpp: a table of angles, any inextensible bend

}  // namespace deformers

const std::vector<const DeformerType*>& deformer_types() {
  static const std::vector<const DeformerType*> types = {
      &deformers::bend(),
      &deformers::hinge(),
      &deformers::spine(),
  };
  return types;
}

}  // namespace finflex

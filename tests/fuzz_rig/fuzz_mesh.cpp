#include "fuzz_mesh.hpp"

#include "finflex/finflex.hpp"
#include "support/synthetic_fish.hpp"

namespace finflex::fuzz {

const Mesh& rig_fuzz_mesh() {
  static const Mesh mesh = [] {
    Mesh fish = test::synthetic_fish(12, 8);
    const std::size_t half = fish.triangle_count() / 2;
    fish.groups = {FaceGroup{"tail", 0, half},
                   FaceGroup{"head", half, fish.triangle_count() - half}};
    return fish;
  }();
  return mesh;
}

void exercise(const Rig& rig) {
  const RiggedMesh model(rig_fuzz_mesh(), rig);
  RigParameters values(model, 2);
  for (const RigParameter& p : model.rig().parameters) {
    for (std::size_t k = 0; k < p.count; ++k) {
      values.values()[p.offset + k] = static_cast<float>(-0.5 * p.limit);
      values.values()[values.values_per_instance() + p.offset + k] =
          static_cast<float>(0.7 * p.limit);
    }
  }
  run_reference(model, values, NormalMode::kJacobian, /*clamp=*/true);
}

}  // namespace finflex::fuzz

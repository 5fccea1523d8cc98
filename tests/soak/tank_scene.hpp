// The swimming tank as a soak scene (apps/tank): fish of one or more species swim
// (tank simulation, swim drivers, placed deformation) at a fixed step. Every `period`
// frames the tank is built again from the same seed, so frames a period apart give
// bit-identical outputs, and every build and teardown of a whole tank is soaked too.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "soak_scene.hpp"

namespace finflex::soak {

std::unique_ptr<SoakScene> make_tank_scene(Context& context, const std::vector<RigSpecies>& species,
                                           std::size_t period, NormalMode normals);

}  // namespace finflex::soak

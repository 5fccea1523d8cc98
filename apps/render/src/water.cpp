#include "render/water.hpp"

#include <cmath>

#include "checks.hpp"

namespace finflex::render {

namespace {

// Pope and Fry (1997), per metre, at kChannelWavelengths (465 nm between their 460 and
// 470 nm values).
constexpr float kPureWaterAbsorption[3] = {0.2644f, 0.0565f, 0.0102f};

float pure_water_scattering(float wavelength) {
  return 0.0022f * std::pow(500.0f / wavelength, 4.32f);
}

}  // namespace

Water water_optics(const WaterComposition& composition) {
  using namespace detail;
  require_in_range("water.turbidity_ntu", composition.turbidity_ntu, 0.0f, 1e4f);
  require_in_range("water.dissolved_absorption_440", composition.dissolved_absorption_440, 0.0f,
                   1e3f);
  Water water;
  for (int c = 0; c < 3; ++c) {
    const float wavelength = kChannelWavelengths[c];
    water.absorption[c] = kPureWaterAbsorption[c] + composition.dissolved_absorption_440 *
                                                        std::exp(-0.014f * (wavelength - 440.0f));
    water.scattering[c] =
        pure_water_scattering(wavelength) + composition.turbidity_ntu * (550.0f / wavelength);
  }
  return water;
}

glm::vec3 downwelling_attenuation(const Water& water, float mu) {
  const glm::vec3 a = water.absorption;
  const glm::vec3 b = water.scattering;
  return glm::sqrt(a * a + (0.425f * mu - 0.19f) * a * b) / mu;
}

}  // namespace finflex::render

// The tank's water as light sees it: what it holds (WaterComposition), and from that
// its inherent optical properties per colour channel (Water), which the renderer's
// image formation uses (docs/rendering.md "Water"). Lengths are metres.
//
// Each channel is taken at one wavelength, the dominant wavelength of its sRGB
// primary: red 610 nm, green 550 nm, blue 465 nm (kChannelWavelengths). The
// properties add up from three parts:
//   pure water   absorption of Pope and Fry (1997, Appl. Opt. 36:8710) at those
//                wavelengths, scattering of Morel (1974): 0.0022 (500 / lambda)^4.32
//   dissolved    coloured dissolved organic matter (the humic "tea" colour that feed
//   organic      and faeces give recirculated water): absorption
//   matter       a_g(lambda) = a_g(440) exp(-0.014 (lambda - 440)) (Bricaud, Morel and
//                Prieur 1981, Limnol. Oceanogr. 26:43)
//   particles    scattering from the turbidity: b_p(550) = 1 m^-1 per NTU, the ratio
//                Kirk gives for turbid natural waters (Light and Photosynthesis in
//                Aquatic Ecosystems, ch. 4, "by a convenient coincidence"), with the
//                lambda^-1 spectral slope usual for particles; their absorption is
//                not modelled (counted in a_g where it matters)
#pragma once

#include <glm/glm.hpp>

namespace finflex::render {

constexpr float kChannelWavelengths[3] = {610.0f, 550.0f, 465.0f};  // nm: red, green, blue

// Per channel, per metre: absorption a and scattering b (beam attenuation c = a + b),
// and the angular shape of the scattering: Henyey and Greenstein's phase function
// (1941, Astrophys. J. 93:70) of asymmetry g, 0.924 fitting Petzold's measured ocean
// phase functions (Mobley, Light and Water, 1994). The key light bends into the water
// at the surface by Snell's law with refractive_index.
struct Water {
  glm::vec3 absorption{0.0f};
  glm::vec3 scattering{0.0f};
  float phase_asymmetry = 0.924f;   // g, 0 <= g < 1
  float refractive_index = 1.333f;  // fresh water; 1.34 for sea water

  glm::vec3 attenuation() const { return absorption + scattering; }
};

struct WaterComposition {
  float turbidity_ntu = 1.0f;             // nephelometric turbidity units, >= 0
  float dissolved_absorption_440 = 0.5f;  // a_g(440 nm) in m^-1, >= 0
};

// The properties of water holding `composition`. RenderError (kInvalidArgument) naming
// "water.turbidity_ntu" or "water.dissolved_absorption_440" when one is negative or
// not finite.
Water water_optics(const WaterComposition& composition);

// Kirk's diffuse attenuation of downwelling light (1991, Limnol. Oceanogr. 36:455):
// K_d = sqrt(a^2 + (0.425 mu - 0.19) a b) / mu, for light travelling at mu = cos of its
// angle from straight down in the water (0 < mu <= 1), per channel.
glm::vec3 downwelling_attenuation(const Water& water, float mu);

}  // namespace finflex::render

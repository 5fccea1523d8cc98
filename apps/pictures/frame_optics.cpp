#include "frame_optics.hpp"

#include <cmath>

#include "finflex/error.hpp"
#include "split_mix.hpp"

namespace finflex::pictures {

namespace {

struct WaterType {
  const char* name;
  render::WaterComposition composition;
};

// Design points, not measurements of any one farm: pure water, a well-kept RAS (the
// default), and a RAS after feeding or with a failing drum filter.
constexpr WaterType kWaterTypes[] = {
    {"clear", {0.0f, 0.0f}},
    {"ras", {1.0f, 0.5f}},
    {"turbid", {10.0f, 2.0f}},
};

}  // namespace

render::WaterComposition water_type(const std::string& name, const std::string& option) {
  for (const WaterType& type : kWaterTypes) {
    if (name == type.name) return type.composition;
  }
  throw Error(ErrorCode::kInvalidArgument, option,
              option + " '" + name + "' is not a water type (" + water_type_names() + ")");
}

const char* water_type_names() { return "clear, ras, turbid"; }

FrameOptics frame_optics(const OpticsSettings& settings, std::size_t frame) {
  if (!settings.vary) return settings.base;
  // One stream per frame: its draws do not depend on the frames before it.
  SplitMix random{settings.seed * 0x9e3779b97f4a7c15ull + frame};
  random.next();
  const OpticsRanges& r = settings.ranges;
  FrameOptics optics;
  optics.water.turbidity_ntu = float(random.uniform(r.turbidity_ntu[0], r.turbidity_ntu[1]));
  optics.water.dissolved_absorption_440 =
      float(random.uniform(r.dissolved_absorption_440[0], r.dissolved_absorption_440[1]));
  optics.light_scale = random.uniform(r.light_scale[0], r.light_scale[1]);
  const double elevation =
      random.uniform(r.light_elevation_degrees[0], r.light_elevation_degrees[1]) * M_PI / 180.0;
  const double azimuth = random.uniform(0.0, 2.0 * M_PI);
  optics.direction_to_light =
      glm::vec3(float(std::cos(elevation) * std::cos(azimuth)), float(std::sin(elevation)),
                float(std::cos(elevation) * std::sin(azimuth)));
  return optics;
}

render::Scene with_optics(const render::Scene& scene, const FrameOptics& optics) {
  render::Scene out = scene;
  const render::Water water = render::water_optics(optics.water);
  out.water.absorption = water.absorption;
  out.water.scattering = water.scattering;
  const auto scale = float(optics.light_scale);
  out.lighting.key_colour *= scale;
  out.lighting.sky_ambient *= scale;
  out.lighting.ground_ambient *= scale;
  if (optics.direction_to_light) out.lighting.direction_to_light = *optics.direction_to_light;
  return out;
}

nlohmann::ordered_json optics_json(const FrameOptics& optics, const render::Scene& drawn) {
  const render::Water& water = drawn.water;
  const auto rgb = [](const glm::vec3& v) { return nlohmann::ordered_json{v.r, v.g, v.b}; };
  const glm::vec3 to_light = glm::normalize(drawn.lighting.direction_to_light);
  return {{"turbidity_ntu", optics.water.turbidity_ntu},
          {"dissolved_absorption_440_per_m", optics.water.dissolved_absorption_440},
          {"wavelengths_nm",
           {render::kChannelWavelengths[0], render::kChannelWavelengths[1],
            render::kChannelWavelengths[2]}},
          {"absorption_per_m", rgb(water.absorption)},
          {"scattering_per_m", rgb(water.scattering)},
          {"attenuation_per_m", rgb(water.attenuation())},
          {"light_scale", optics.light_scale},
          {"direction_to_light", rgb(to_light)}};
}

}  // namespace finflex::pictures

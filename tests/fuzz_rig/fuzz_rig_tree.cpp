// libFuzzer: bytes as a RigSpec built in code (the resolver without the JSON): up to
// 300 components with parents by name (self, unknown, cycles, chains deeper than
// kMaxRigDepth), every selector kind with arbitrary numbers (NaN, huge, zero), frames
// of every mode, stages of every deformer with arbitrary option values. Then
// resolve_rig, the model and one reference frame; only finflex::Error may come out.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "finflex/deformer_type.hpp"
#include "finflex/error.hpp"
#include "finflex/rig.hpp"
#include "fuzz_mesh.hpp"

namespace {

using namespace finflex;

double any_double(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 7)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return std::numeric_limits<double>::infinity() * (in.ConsumeBool() ? 1 : -1);
    case 2:
      return 0.0;
    case 3:
      return in.ConsumeFloatingPoint<double>();
    default:
      return in.ConsumeFloatingPointInRange<double>(-2.0, 2.0);
  }
}

glm::dvec3 any_vec3(FuzzedDataProvider& in) {
  return {any_double(in), any_double(in), any_double(in)};
}

FrameSpec any_frame(FuzzedDataProvider& in) {
  FrameSpec frame;
  frame.mode = static_cast<FrameSpec::Mode>(in.ConsumeIntegralInRange<int>(0, 2));
  frame.origin = any_vec3(in);
  frame.x = any_vec3(in);
  frame.y = any_vec3(in);
  if (in.ConsumeBool()) frame.length = any_double(in);
  return frame;
}

SelectorSpec any_selector(FuzzedDataProvider& in) {
  SelectorSpec select;
  select.kind = static_cast<SelectorSpec::Kind>(in.ConsumeIntegralInRange<int>(0, 4));
  const std::size_t indices = in.ConsumeIntegralInRange<std::size_t>(0, 40);
  for (std::size_t k = 0; k < indices; ++k) {
    select.indices.push_back(in.ConsumeBool() ? in.ConsumeIntegralInRange<std::uint32_t>(0, 90)
                                              : in.ConsumeIntegral<std::uint32_t>());
  }
  select.group = in.PickValueInArray<const char*>({"head", "tail", "fin", ""});
  select.box_min = any_vec3(in);
  select.box_max = any_vec3(in);
  select.point = any_vec3(in);
  select.normal = any_vec3(in);
  return select;
}

StageSpec any_stage(FuzzedDataProvider& in) {
  const auto& types = deformer_types();
  StageSpec stage;
  stage.deformer = in.ConsumeIntegralInRange<int>(0, 15) == 0
                       ? nullptr
                       : types[in.ConsumeIntegralInRange<std::size_t>(0, types.size() - 1)];
  if (stage.deformer != nullptr) stage.options = default_options(*stage.deformer);
  if (in.ConsumeBool()) {
    for (double& option : stage.options) option = any_double(in);
  }
  stage.param = in.PickValueInArray<const char*>({"a", "b", "m", "tail_angle", ""});
  return stage;
}

std::string name_of(std::size_t k) { return "c" + std::to_string(k); }

RigSpec any_spec(FuzzedDataProvider& in) {
  RigSpec spec;
  spec.frame = any_frame(in);
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 300);
  const bool chain = in.ConsumeBool();  // parents mostly k - 1: deep trees
  for (std::size_t k = 0; k < n && in.remaining_bytes() > 0; ++k) {
    ComponentSpec component;
    component.name = in.ConsumeIntegralInRange<int>(0, 30) == 0 ? "" : name_of(k);
    if (k > 0) {
      const int how = in.ConsumeIntegralInRange<int>(0, 9);
      component.parent = how == 0           ? std::string()
                         : how == 1         ? std::string("nobody")
                         : chain && how > 3 ? name_of(k - 1)
                                            : name_of(in.ConsumeIntegralInRange<std::size_t>(0, n));
    }
    component.select = k == 0 && in.ConsumeBool() ? SelectorSpec{} : any_selector(in);
    if (in.ConsumeBool()) component.frame = any_frame(in);
    const std::size_t stages = in.ConsumeIntegralInRange<std::size_t>(0, 6);
    for (std::size_t s = 0; s < stages; ++s) component.chain.push_back(any_stage(in));
    spec.components.push_back(component);
  }
  return spec;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  try {
    const RigSpec spec = any_spec(in);
    fuzz::exercise(resolve_rig(spec, fuzz::rig_fuzz_mesh()));
  } catch (const Error&) {
  }
  return 0;
}

#include "swim_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace finflex::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void invalid(const char* field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, message);
}

// Straight ahead at `speed_m_s`, towards +z (yaw -pi/2: yaw 0 is +x, pi/2 is -z), level.
SwimInput steady(double speed_m_s) {
  SwimInput input;
  input.yaw = static_cast<float>(-0.5 * kPi);
  input.speed = static_cast<float>(speed_m_s);
  return input;
}

}  // namespace

void CycleSettings::validate() const {
  if (frames < 2 || frames > 10000) {
    invalid("frames", "frames = " + std::to_string(frames) + " (expected 2 to 10,000)");
  }
  if (!std::isfinite(length_m) || !(length_m > 0.0)) {
    invalid("length", "length = " + std::to_string(length_m) + " m (expected > 0)");
  }
  if (!std::isfinite(speed) || speed < 0.0 || speed > 20.0) {
    invalid("speed",
            "speed = " + std::to_string(speed) + " body lengths per second (expected 0 to 20)");
  }
}

SwimCycle plan_cycle(const SwimModel& swim, const CycleSettings& settings) {
  settings.validate();
  const std::vector<float> length = {static_cast<float>(settings.length_m)};
  const std::vector<SwimInput> input = {steady(settings.speed * double(length[0]))};
  SwimReference probe(swim, length);  // f depends on the length and speed alone
  probe.step(input, 1e-3);
  const std::size_t n = settings.frames;
  SwimCycle cycle{probe.frequencies()[0], 0.0, 0.0, n, RigParameters(swim.model(), n + 1), {}};
  cycle.period_s = 1.0 / cycle.frequency_hz;
  cycle.dt_s = cycle.period_s / double(n);

  SwimReference fish(swim, length);
  const std::size_t values = cycle.parameters.values_per_instance();
  for (std::size_t step = 1; step <= n; ++step) {
    fish.step(input, cycle.dt_s);
    const std::vector<float>& row = fish.parameters().values();
    std::copy(row.begin(), row.begin() + std::ptrdiff_t(values),
              cycle.parameters.values().begin() + std::ptrdiff_t((step % n) * values));
  }
  cycle.placements.assign(n + 1, fish.placements()[0]);
  return cycle;
}

BakedCycle bake_cycle(Context& context, const SwimModel& swim, const CycleSettings& settings) {
  BakedCycle baked{plan_cycle(swim, settings), {}};
  ClDeformer deformer(context, swim.model());
  DeviceBatch batch = deformer.allocate(baked.cycle.frames + 1);
  ClJob job;
  job.instances = baked.cycle.parameters.instance_count();
  job.parameters = baked.cycle.parameters.view();
  job.placements = baked.cycle.placements.data();
  job.normals = settings.normals;
  job.outputs = &batch;
  deformer.enqueue(job);
  baked.batch = deformer.read(batch);
  return baked;
}

}  // namespace finflex::bake

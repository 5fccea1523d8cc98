// The level choice of finflex/level_choice.hpp on the device: culling, levels and the
// compacted lists of a hall of fish, timed by profiling events from the first kernel's
// start to the last's end, after a warm-up. Counters: visible (the share of fish in
// view), vertices/frame (what the chosen levels deform) and full_vertices/frame (the
// same fish at full detail, culled ones included, as without levels).
//
// The hall: 8 round tanks 8 m across and 2.5 m deep, 2 rows of 4 at 10 m centres, fish
// 0.2 to 0.6 m long spread through the water; a 1920 x 1080 camera with a 50 degree
// field of view 4 m above the floor at one end, looking down the hall. The second
// argument 1: the tanks' walls (2.75 m, 96 faces) hide the fish behind them
// (LevelChooser::set_occluders).
#include <random>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

glm::dvec3 tank_centre(std::size_t tank) {
  return {-15.0 + 10.0 * double(tank % 4), 0.0, -5.0 - 10.0 * double(tank / 4)};
}

std::vector<PlacementRecord> hall_of_fish(std::size_t count) {
  std::mt19937 random(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PlacementRecord> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t tank = i % 8;
    const double cx = tank_centre(tank).x, cz = tank_centre(tank).z;
    const double r = 3.8 * std::sqrt(unit(random)), a = 6.283185307179586 * unit(random);
    Placement p;
    p.position = glm::vec3(float(cx + r * std::cos(a)), float(0.2 + 2.1 * unit(random)),
                           float(cz + r * std::sin(a)));
    p.orientation = glm::quat(glm::vec3(0.0f, float(a + 1.5707963), 0.0f));
    p.length = float(0.2 + 0.4 * unit(random));
    out.push_back(placement_record(p));
  }
  return out;
}

void BM_LevelChoice(benchmark::State& state) {
  Setup& setup = Setup::get();
  static const DetailLevels levels = make_detail_levels(setup.rig().model, LevelOptions{});
  const std::size_t count = static_cast<std::size_t>(state.range(0));
  const std::vector<PlacementRecord> records = hall_of_fish(count);
  cl::Buffer placements(setup.context.context(), CL_MEM_READ_ONLY,
                        records.size() * sizeof(PlacementRecord));
  check_cl(setup.context.queue().enqueueWriteBuffer(
               placements, CL_TRUE, 0, records.size() * sizeof(PlacementRecord), records.data()),
           "clEnqueueWriteBuffer");
  LevelChooser chooser(setup.context, levels, count);
  if (state.range(1) != 0) {
    std::vector<WallOccluder> walls;
    for (std::size_t t = 0; t < 8; ++t) walls.push_back({tank_centre(t), 4.0, 2.75, 96});
    chooser.set_occluders(walls);
  }
  const std::vector<LevelView> views{LevelView::look_at({-19.0, 4.0, 2.0}, {5.0, 0.5, -20.0},
                                                        {0, 1, 0}, 50.0, 1920, 1080, 0.1, 80.0)};
  std::vector<cl::Event> kernels;
  time_iterations(state, [&] {
    chooser.enqueue(placements, count, views, nullptr, &kernels);
    return span_seconds(kernels.front(), kernels.back());
  });
  const LevelChooser::Choice choice = chooser.read();
  double visible = 0.0, vertices = 0.0;
  for (std::size_t k = 0; k < choice.lists.size(); ++k) {
    visible += double(choice.lists[k].size());
    vertices += double(choice.lists[k].size()) * double(levels.level(k).vertex_count);
  }
  state.counters["visible"] = visible / double(count);
  state.counters["vertices/frame"] = vertices;
  state.counters["full_vertices/frame"] = double(count) * double(levels.level(0).vertex_count);
}

BENCHMARK(BM_LevelChoice)
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(0.5);

}  // namespace
}  // namespace finflex::bench

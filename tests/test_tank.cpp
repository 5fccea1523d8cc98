// The virtual RAS tank (apps/tank/): deterministic for a seed, fish that stay inside
// the water and never become NaN over 10,000 steps, bad settings named, and a swim
// scene whose deformed fish are where the tank says.
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "hall.hpp"
#include "support/test_support.hpp"
#include "swim_scene.hpp"
#include "tank.hpp"

namespace finflex::tank {
namespace {

TEST(Tank, TheSameSeedGivesTheSameTank) {
  Tank a(TankSettings{}, {30, 20}, 7), b(TankSettings{}, {30, 20}, 7),
      c(TankSettings{}, {30, 20}, 8);
  for (int step = 0; step < 100; ++step) {
    a.step(1.0 / 30.0);
    b.step(1.0 / 30.0);
    c.step(1.0 / 30.0);
  }
  double difference = 0.0;
  for (std::size_t i = 0; i < a.fish().size(); ++i) {
    EXPECT_EQ(a.fish()[i].position, b.fish()[i].position);
    EXPECT_EQ(a.fish()[i].yaw, b.fish()[i].yaw);
    difference = std::max(difference, glm::length(a.fish()[i].position - c.fish()[i].position));
  }
  EXPECT_GT(difference, 0.01);  // another seed, another tank
}

// A hall of tanks: the fish spread over them, each in its own tank's water (its axis
// centre(t)), the inputs in hall coordinates tank by tank, bad settings named.
TEST(Hall, EachTanksFishSwimInThatTankWhereTheHallPutsIt) {
  HallSettings settings = HallSettings::farm(6, 3000);
  settings.columns = 3;
  EXPECT_EQ(settings.tank.diameter, TankSettings{}.diameter);  // 500 a tank: no scaling
  const HallSettings big = HallSettings::farm(16, 100000);
  EXPECT_NEAR(big.tank.diameter, TankSettings{}.diameter * std::cbrt(6.25), 1e-12);
  Hall hall(settings, {1700, 1300}, 9);
  ASSERT_EQ(hall.tank_count(), 6u);
  EXPECT_DOUBLE_EQ(hall.spacing(), settings.tank.diameter + settings.walkway);
  EXPECT_EQ(hall.centre(4), glm::dvec3(hall.spacing(), 0.0, -hall.spacing()));
  // Each tank's wall as an occluder: its axis, radius, rim (10 % above the water), faces.
  const std::vector<WallOccluder> walls = hall.walls();
  ASSERT_EQ(walls.size(), 6u);
  EXPECT_EQ(walls[4].base, hall.centre(4));
  EXPECT_DOUBLE_EQ(walls[4].radius, 0.5 * settings.tank.diameter);
  EXPECT_DOUBLE_EQ(walls[4].height, 1.1 * settings.tank.depth);
  EXPECT_EQ(walls[4].sides, 96);
  for (int step = 0; step < 60; ++step) hall.step(1.0 / 30.0);
  ASSERT_EQ(hall.fish().size(), 3000u);
  std::size_t index = 0;
  for (std::size_t t = 0; t < hall.tank_count(); ++t) {
    EXPECT_EQ(hall.tank(t).fish().size(), 500u);
    for (const Fish& local : hall.tank(t).fish()) {
      const Fish& fish = hall.fish()[index++];
      EXPECT_EQ(fish.position, local.position + hall.centre(t));
      const glm::dvec3 in_tank = fish.position - hall.centre(t);
      EXPECT_LE(std::hypot(in_tank.x, in_tank.z), 0.5 * settings.tank.diameter);
    }
  }
  EXPECT_EQ(hall.corrections(), 0u);
  std::vector<SwimInput> inputs;
  hall.inputs(1, inputs);
  ASSERT_EQ(inputs.size(), 1300u);
  std::vector<SwimInput> staged(1300);
  hall.inputs(1, staged.data());
  std::size_t k = 0;
  for (const Fish& fish : hall.fish()) {
    if (fish.species != 1) continue;
    EXPECT_EQ(inputs[k].position, glm::vec3(fish.position));
    EXPECT_EQ(staged[k].position, inputs[k].position);
    ++k;
  }
  EXPECT_EQ(hall.lengths(1).size(), 1300u);

  auto field_of = [](HallSettings bad, std::vector<std::size_t> fish) {
    try {
      Hall rejected(bad, fish, 1);
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  HallSettings none = settings;
  none.tanks = 0;
  EXPECT_EQ(field_of(none, {10}), "hall.tanks");
  HallSettings flat = settings;
  flat.columns = 0;
  EXPECT_EQ(field_of(flat, {10}), "hall.columns");
  HallSettings crowded = settings;
  crowded.walkway = -1.0;
  EXPECT_EQ(field_of(crowded, {10}), "hall.walkway");
  EXPECT_EQ(field_of(settings, {3, 2}), "fish");  // 6 tanks, 5 fish
}

TEST(Tank, FishStayInTheWaterAndFiniteForTenThousandSteps) {
  const TankSettings settings;
  Tank tank(settings, {150, 50}, 3);
  const double radius = 0.5 * settings.diameter;
  for (int step = 0; step < 10000; ++step) {
    tank.step(1.0 / 30.0);
    for (const Fish& fish : tank.fish()) {
      ASSERT_TRUE(std::isfinite(fish.position.x) && std::isfinite(fish.position.y) &&
                  std::isfinite(fish.position.z) && std::isfinite(fish.yaw) &&
                  std::isfinite(fish.speed) && std::isfinite(fish.turn_rate))
          << "step " << step;
      ASSERT_LE(std::hypot(fish.position.x, fish.position.z), radius) << "step " << step;
      ASSERT_GE(fish.position.y, 0.0);
      ASSERT_LE(fish.position.y, settings.depth);
      ASSERT_GE(fish.speed, 0.0);
      ASSERT_LE(std::fabs(fish.turn_rate), settings.max_yaw_rate + 1e-12);
    }
  }
  // Steering and braking keep them in the water: no fish is ever put back.
  EXPECT_EQ(tank.corrections(), 0u);
}

// `steps` steps of 1,000 fish (two species) at 30 a second: no correction, braking rare.
void expect_no_correction(int steps) {
  Tank tank(TankSettings{}, {500, 500}, 5);
  for (int step = 0; step < steps; ++step) tank.step(1.0 / 30.0);
  EXPECT_EQ(tank.corrections(), 0u);
  for (const Fish& fish : tank.fish()) {
    ASSERT_TRUE(std::isfinite(fish.position.x) && std::isfinite(fish.position.y) &&
                std::isfinite(fish.position.z));
  }
  // Braking is the exception: a turning fish in front of a boundary, not the rule.
  EXPECT_LT(double(tank.brakes()) / (double(steps) * 1000.0), 0.01) << tank.brakes();
  std::printf("1,000 fish, %d steps: %zu corrections, %zu brakes (%.3f %% of fish-steps)\n", steps,
              tank.corrections(), tank.brakes(),
              100.0 * double(tank.brakes()) / (double(steps) * 1000.0));
}

TEST(Tank, AThousandFishNeedNoCorrectionInTwoThousandSteps) { expect_no_correction(2000); }
TEST(TankLarge, AThousandFishNeedNoCorrectionInTenThousandSteps) { expect_no_correction(10000); }

// Schooling: each fish's heading agrees more with its neighbours' with alignment and
// cohesion than without (local order: the mean over fish of the length of the mean
// heading of the fish and its neighbours within 0.4 m, 1 when all agree; its disorder:
// 1 less it), and they still need no correction.
double local_order(const Tank& tank) {
  const std::vector<Fish>& fish = tank.fish();
  double sum = 0.0;
  for (const Fish& a : fish) {
    glm::dvec2 mean(0.0);
    double count = 0.0;
    for (const Fish& b : fish) {
      if (glm::length(a.position - b.position) >= 0.4) continue;
      mean += glm::dvec2(std::cos(b.yaw), std::sin(b.yaw));
      count += 1.0;
    }
    sum += glm::length(mean) / count;
  }
  return sum / double(fish.size());
}

TEST(Tank, NeighboursSwimAlongEachOtherWhenSchooling) {
  TankSettings alone;
  alone.alignment = 0.0;
  alone.cohesion = 0.0;
  Tank schooling(TankSettings{}, {600}, 3), solitary(alone, {600}, 3);
  for (int step = 0; step < 300; ++step) {
    schooling.step(1.0 / 30.0);
    solitary.step(1.0 / 30.0);
  }
  const double with = local_order(schooling), without = local_order(solitary);
  std::printf("local order of 600 fish after 10 s: %.3f schooling, %.3f without\n", with, without);
  // Heading into the current aligns neighbours already (about 0.94); schooling takes a
  // quarter of the rest of the disorder away.
  EXPECT_LT(1.0 - with, 0.85 * (1.0 - without));
  EXPECT_EQ(schooling.corrections(), 0u);
  TankSettings bad;
  bad.alignment = -0.5;
  EXPECT_THROW(Tank(bad, {10}, 1), Error);
  bad = TankSettings{};
  bad.cohesion = std::nan("");
  try {
    Tank rejected(bad, {10}, 1);
    ADD_FAILURE() << "a NaN cohesion was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "tank.cohesion");
  }
}

TEST(Tank, FishSwimAgainstTheCurrent) {
  Tank tank(TankSettings{}, {100}, 11);
  for (int step = 0; step < 300; ++step) tank.step(1.0 / 30.0);
  double upstream = 0.0;
  for (const Fish& fish : tank.fish()) {
    const glm::dvec3 heading(std::cos(fish.yaw), 0.0, -std::sin(fish.yaw));
    const glm::dvec3 flow = tank.current(fish.position);
    if (glm::length(flow) > 1e-6) upstream += glm::dot(heading, -glm::normalize(flow));
  }
  EXPECT_GT(upstream / 100.0, 0.5);  // mostly heading into the current (positive rheotaxis)
}

TEST(Tank, BadSettingsAreNamed) {
  auto field_of = [](TankSettings settings, std::vector<std::size_t> fish) {
    try {
      Tank tank(settings, fish, 1);
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  TankSettings small;
  small.diameter = 1.0;  // under 4 lengths of 0.4 m
  EXPECT_EQ(field_of(small, {10}), "tank.diameter");
  TankSettings shallow;
  shallow.depth = 0.5;
  EXPECT_EQ(field_of(shallow, {10}), "tank.depth");
  TankSettings nan_depth;
  nan_depth.depth = NAN;
  EXPECT_EQ(field_of(nan_depth, {10}), "tank.depth");
  TankSettings rimless;
  rimless.freeboard = -0.1;
  EXPECT_EQ(field_of(rimless, {10}), "tank.freeboard");
  TankSettings faceted;
  faceted.wall_faces = 4;
  EXPECT_EQ(field_of(faceted, {10}), "tank.wall_faces");
  EXPECT_EQ(field_of(TankSettings{}, {0, 0}), "fish");
  EXPECT_EQ(field_of(TankSettings{}, {1}), "accepted");
  Tank tank(TankSettings{}, {1}, 1);
  EXPECT_THROW(tank.step(0.0), Error);
  EXPECT_THROW(parse_species("fish.obj", "--species"), Error);
  EXPECT_EQ(parse_species("a/b:c.obj:rig.json", "--species").rig, "rig.json");
}

TEST(SwimScene, DeformedFishAreWhereTheTankPutsThem) {
  SwimScene scene(test::shared_context(), bundled_species(test::data_path("")), 6, TankSettings{},
                  5, NormalMode::kJacobian);
  for (int frame = 0; frame < 3; ++frame) scene.enqueue_frame(1.0 / 30.0);
  ASSERT_EQ(scene.species().size(), 2u);
  std::size_t index = 0;
  for (std::size_t s = 0; s < 2; ++s) {
    Species& species = scene.species()[s];
    const DeformedBatch<float> batch = species.deformer->read(species.batch());
    for (std::size_t i = 0; i < batch.shape.instance_count; ++i, ++index) {
      // The fish (in tank order, species by species) is within a body length of where
      // the tank says its pivot is.
      const Fish* fish = nullptr;
      std::size_t seen = 0;
      for (const Fish& f : scene.hall().fish()) {
        if (f.species == s && seen++ == i) fish = &f;
      }
      ASSERT_NE(fish, nullptr);
      glm::dvec3 centre(0.0);
      for (std::size_t v = 0; v < batch.shape.vertex_count; ++v)
        centre += glm::dvec3(batch.position(i, v));
      centre /= double(batch.shape.vertex_count);
      EXPECT_LT(glm::length(centre - fish->position), fish->length) << species.name << " " << i;
    }
  }
}

// A frame from inputs the caller writes (SwimScene::enqueue_frame with a writer, as
// `finflex bench --swim` replays recorded steps) deforms the fish as the tank's own
// frame does from the same inputs; the tank does not step for it.
TEST(SwimScene, FramesFromTheCallersInputsMatchTheTanksOwn) {
  const auto scene = [] {
    return std::make_unique<SwimScene>(test::shared_context(), bundled_species(test::data_path("")),
                                       5, TankSettings{}, 7, NormalMode::kRotate);
  };
  const auto own = scene();
  const auto written = scene();
  constexpr double kDt = 1.0 / 30.0;
  for (int frame = 0; frame < 3; ++frame) {
    own->enqueue_frame(kDt);
    written->hall().step(kDt);
    const double time = written->hall().time();
    std::vector<std::size_t> asked;
    const FrameWork work = written->enqueue_frame(
        kDt,
        [&](std::size_t species, SwimInput* staged) {
          asked.push_back(species);
          written->hall().inputs(species, staged);
        },
        true);
    EXPECT_EQ(written->hall().time(), time);  // no step of its own
    EXPECT_EQ(asked, (std::vector<std::size_t>{0, 1}));
    EXPECT_FALSE(work.kernels.empty());
  }
  for (std::size_t s = 0; s < 2; ++s) {
    SCOPED_TRACE(own->species()[s].name);
    const DeformedBatch<float> a = own->species()[s].deformer->read(own->species()[s].batch());
    const DeformedBatch<float> b =
        written->species()[s].deformer->read(written->species()[s].batch());
    ASSERT_EQ(a.shape.instance_count, b.shape.instance_count);
    for (std::size_t i = 0; i < a.shape.instance_count; ++i) {
      for (std::size_t v = 0; v < a.shape.vertex_count; ++v) {
        ASSERT_EQ(a.position(i, v), b.position(i, v)) << i << " " << v;
        ASSERT_EQ(a.normal(i, v), b.normal(i, v)) << i << " " << v;
      }
    }
  }
}

}  // namespace
}  // namespace finflex::tank

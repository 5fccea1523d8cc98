// The level choice on the device (finflex/level_choice.hpp): against its host twin and
// against the camera's geometry computed here, the lists and draw arguments, the
// hysteresis, the same lists for the same frame, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

const RiggedMesh& blub() {
  static const RiggedMesh model = [] {
    Mesh mesh = load_mesh(test::data_path("blub/fish.obj"));
    compute_vertex_normals(mesh);
    return RiggedMesh(mesh,
                      resolve_rig(load_rig_file(test::data_path("rigs/blub_swim.rig.json")), mesh));
  }();
  return model;
}

const DetailLevels& blub_levels() {
  static const DetailLevels levels = make_detail_levels(blub(), LevelOptions{});
  return levels;
}

// A camera at the origin's side of a farm hall, looking along -z.
const glm::dvec3 kEye{0.0, 2.0, 6.0};
const glm::dvec3 kTarget{0.0, 0.5, -20.0};
constexpr double kFov = 40.0;
constexpr int kWidth = 1920, kHeight = 1080;
constexpr double kNear = 0.1, kFar = 60.0;

LevelView camera() {
  return LevelView::look_at(kEye, kTarget, {0, 1, 0}, kFov, kWidth, kHeight, kNear, kFar);
}

// Fish scattered over a volume wider than the view: some in front, some behind, some
// beside, at depths from under a metre to past the far plane.
std::vector<Placement> scattered(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(-30.0, 30.0), y(-2.0, 4.0), z(-70.0, 10.0);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), length(0.2, 0.6);
  std::vector<Placement> out(count);
  for (Placement& p : out) {
    p.position = glm::vec3(float(x(random)), float(y(random)), float(z(random)));
    p.orientation = glm::quat(glm::vec3(0.3f * float(angle(random)), float(angle(random)), 0.0f));
    p.length = float(length(random));
  }
  return out;
}

std::vector<PlacementRecord> records_of(const std::vector<Placement>& placements) {
  std::vector<PlacementRecord> out;
  for (const Placement& p : placements) out.push_back(placement_record(p));
  return out;
}

cl::Buffer upload(const std::vector<PlacementRecord>& records) {
  Context& context = test::shared_context();
  cl::Buffer buffer(context.context(), CL_MEM_READ_ONLY, records.size() * sizeof(PlacementRecord));
  check_cl(context.queue().enqueueWriteBuffer(
               buffer, CL_TRUE, 0, records.size() * sizeof(PlacementRecord), records.data()),
           "clEnqueueWriteBuffer");
  return buffer;
}

// The camera's axes, from its eye and target (not from the matrices the library made).
struct Axes {
  glm::dvec3 forward, right, up;
};
Axes axes() {
  Axes a;
  a.forward = glm::normalize(kTarget - kEye);
  a.right = glm::normalize(glm::cross(a.forward, glm::dvec3(0, 1, 0)));
  a.up = glm::cross(a.right, a.forward);
  return a;
}

// Whether a point is inside the camera's frustum, from its angles.
bool inside_frustum(const glm::dvec3& p) {
  const Axes a = axes();
  const glm::dvec3 d = p - kEye;
  const double depth = glm::dot(d, a.forward);
  if (depth < kNear || depth > kFar) return false;
  const double tan_y = std::tan(0.5 * glm::radians(kFov));
  const double tan_x = tan_y * double(kWidth) / double(kHeight);
  return std::abs(glm::dot(d, a.right)) <= depth * tan_x &&
         std::abs(glm::dot(d, a.up)) <= depth * tan_y;
}

glm::dvec3 sphere_centre(const Placement& p, const BodyBounds& bounds) {
  return glm::dvec3(p.position) +
         double(p.length) * (glm::mat3_cast(glm::dquat(p.orientation)) * bounds.centre);
}

// The choice of `levels` at `budget` pixels against the host's and the camera's, its
// lists and draw arguments; with `every_level`, the scene puts fish at every level.
// `fish_per_level`: the fish at each level.
void check_choice(const DetailLevels& levels, double budget, bool every_level,
                  std::vector<std::size_t>* fish_per_level = nullptr) {
  const std::size_t count = 3000;
  const std::vector<Placement> placements = scattered(count, 7);
  const std::vector<PlacementRecord> records = records_of(placements);
  const cl::Buffer buffer = upload(records);
  LevelChoiceOptions options;
  options.pixel_budget = budget;
  LevelChooser chooser(test::shared_context(), levels, count, options);
  const std::vector<LevelView> views{camera()};
  chooser.enqueue(buffer, count, views);
  const LevelChooser::Choice choice = chooser.read();
  ASSERT_EQ(choice.level_of.size(), count);

  const BodyBounds bounds = body_bounds(levels.level(0).model);
  const std::vector<double> errors = level_errors(levels);
  const double focal = double(kHeight) / (2.0 * std::tan(0.5 * glm::radians(kFov)));
  std::size_t visible = 0, borderline = 0;
  std::vector<std::size_t> per_level(levels.size(), 0);
  for (std::size_t i = 0; i < count; ++i) {
    const int level = choice.level_of[i];
    const int host = choose_level_on_host(records[i], bounds, errors, views, options, -1);
    if (level != host) {
      // Only where float's rounding decides: a budget a hair larger or smaller agrees.
      LevelChoiceOptions looser = options, tighter = options;
      looser.pixel_budget *= 1.0 + 1e-5;
      tighter.pixel_budget *= 1.0 - 1e-5;
      EXPECT_TRUE(choose_level_on_host(records[i], bounds, errors, views, looser, -1) == level ||
                  choose_level_on_host(records[i], bounds, errors, views, tighter, -1) == level)
          << "instance " << i << ": device " << level << ", host " << host;
      ++borderline;
    }
    const glm::dvec3 centre = sphere_centre(placements[i], bounds);
    if (level < 0) {
      EXPECT_FALSE(inside_frustum(centre)) << "instance " << i << " culled with its centre in view";
      continue;
    }
    ++visible;
    ++per_level[std::size_t(level)];
    // The chosen level's error, projected here from the eye: within the budget.
    const double radius = double(placements[i].length) * bounds.radius;
    const double depth = std::max(glm::dot(centre - kEye, axes().forward) - radius, kNear);
    const double pixels = errors[std::size_t(level)] * double(placements[i].length) * focal / depth;
    EXPECT_LE(pixels, options.pixel_budget * (1.0 + 1e-5)) << "instance " << i;
  }
  EXPECT_LE(borderline, 3u);
  // The scene exercises every outcome: culled fish, and fish at every level.
  EXPECT_GT(visible, count / 10);
  EXPECT_LT(visible, count);
  for (std::size_t k = 0; every_level && k < per_level.size(); ++k)
    EXPECT_GT(per_level[k], 0u) << "level " << k;

  // The lists: each level's instances, ascending; their counts in the draw arguments.
  ASSERT_EQ(choice.lists.size(), levels.size());
  for (std::size_t k = 0; k < choice.lists.size(); ++k) {
    std::vector<std::uint32_t> expected;
    for (std::size_t i = 0; i < count; ++i) {
      if (choice.level_of[i] == int(k)) expected.push_back(std::uint32_t(i));
    }
    EXPECT_EQ(choice.lists[k], expected) << "level " << k;
    EXPECT_EQ(choice.draw_arguments[5 * k], levels.level(k).triangle_count * 3);
    EXPECT_EQ(choice.draw_arguments[5 * k + 1], expected.size());
    for (int c = 2; c < 5; ++c) EXPECT_EQ(choice.draw_arguments[5 * k + std::size_t(c)], 0u);
  }

  // The same placements chosen afresh: the same levels and lists, bit for bit.
  chooser.forget();
  chooser.enqueue(buffer, count, views);
  const LevelChooser::Choice again = chooser.read();
  EXPECT_EQ(again.level_of, choice.level_of);
  EXPECT_EQ(again.lists, choice.lists);
  if (fish_per_level) *fish_per_level = per_level;
}

TEST(LevelChoice, TheDeviceChoosesAsTheHostAndAsTheCameraSees) {
  // A quarter-pixel budget: the nearest fish need the full mesh (its levels' errors are
  // small enough that at one pixel none does in this scene).
  check_choice(blub_levels(), 0.25, true);
}

TEST(LevelChoice, NineLevelsChooseAsTheHost) {
  // 8 levels of the mesh and the frozen-fin one: the kernels' wider per-level counts.
  LevelOptions options;
  options.levels = 8;
  options.triangle_ratio = 0.5;
  options.freeze_fins = true;
  options.value_bounds = SwimModel(blub()).value_bounds();
  const DetailLevels nine = make_detail_levels(blub(), options);
  ASSERT_EQ(nine.size(), 9u);
  // At 4 pixels the farthest fish take the frozen level (the ninth list).
  std::vector<std::size_t> per_level(9, 0);
  check_choice(nine, 4.0, false, &per_level);
  EXPECT_GT(per_level[8], 0u);
  EXPECT_GT(per_level[7], 0u);
}

// The lists as the room rule says, from each instance's level: a level's own instances
// in order, then those past the rows of the finer level, each kept where it has room.
struct Placed {
  std::vector<std::vector<std::uint32_t>> lists;
  std::uint32_t undrawn = 0;
};
Placed place_in_rows(const std::vector<int>& level_of, const std::vector<std::size_t>& rows) {
  Placed out;
  out.lists.resize(rows.size());
  std::vector<std::uint32_t> incoming;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::vector<std::uint32_t> sequence;
    for (std::size_t i = 0; i < level_of.size(); ++i) {
      if (level_of[i] == int(k)) sequence.push_back(std::uint32_t(i));
    }
    sequence.insert(sequence.end(), incoming.begin(), incoming.end());
    const std::size_t kept = std::min(rows[k], sequence.size());
    out.lists[k].assign(sequence.begin(), sequence.begin() + std::ptrdiff_t(kept));
    incoming.assign(sequence.begin() + std::ptrdiff_t(kept), sequence.end());
  }
  out.undrawn = std::uint32_t(incoming.size());
  return out;
}

TEST(LevelChoice, EveryViewCountsOnTheDeviceAsOnTheHost) {
  // Two to four views (a stereo pair, cameras around the tank): the device takes each
  // fish's finest need over the views that see it, as the host does.
  const std::size_t count = 3000;
  const std::vector<PlacementRecord> records = records_of(scattered(count, 11));
  const cl::Buffer buffer = upload(records);
  LevelChoiceOptions options;
  options.pixel_budget = 0.25;
  const BodyBounds bounds = body_bounds(blub_levels().level(0).model);
  const std::vector<double> errors = level_errors(blub_levels());
  const glm::dvec3 eyes[3] = {kEye + glm::dvec3(0.3, 0.0, 0.0), glm::dvec3(4.0, 1.0, 0.0),
                              glm::dvec3(-3.0, 2.0, -1.0)};
  std::vector<LevelView> views{camera()};
  for (const glm::dvec3& eye : eyes) {
    views.push_back(
        LevelView::look_at(eye, kTarget, {0, 1, 0}, kFov, kWidth, kHeight, kNear, kFar));
    LevelChooser chooser(test::shared_context(), blub_levels(), count, options);
    chooser.enqueue(buffer, count, views);
    const LevelChooser::Choice choice = chooser.read();
    std::size_t differ = 0, visible = 0;
    for (std::size_t i = 0; i < count; ++i) {
      differ += choice.level_of[i] !=
                choose_level_on_host(records[i], bounds, errors, views, options, -1);
      visible += choice.level_of[i] >= 0;
    }
    EXPECT_LE(differ, 3u) << views.size() << " views";  // float's rounding at a budget's edge
    EXPECT_GT(visible, count / 10) << views.size() << " views";
  }
}

TEST(LevelChoice, WallsHideFishOnTheDeviceAsOnTheHost) {
  // A hall of 4 x 4 tanks (the farm's: 3.66 m across, 1.34 m walls, 1 m walkways), fish
  // in their water, seen from the gangway 4 m up: the far rows' fish behind the nearer
  // tanks' walls are culled on the device as on the host.
  const double spacing = 4.66, radius = 1.83, wall_height = 1.34;
  std::vector<WallOccluder> walls;
  for (int t = 0; t < 16; ++t) {
    walls.push_back({{(t % 4) * spacing, 0.0, -(t / 4) * spacing}, radius, wall_height, 96});
  }
  const std::size_t count = 4000;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Placement> placements(count);
  for (std::size_t i = 0; i < count; ++i) {
    const WallOccluder& tank = walls[i % walls.size()];
    const double r = 1.5 * std::sqrt(unit(random)), a = 6.283185307179586 * unit(random);
    placements[i].position = glm::vec3(glm::dvec3(
        tank.base.x + r * std::cos(a), 0.15 + 0.9 * unit(random), tank.base.z + r * std::sin(a)));
    placements[i].orientation = glm::quat(glm::vec3(0.0f, float(a), 0.0f));
    placements[i].length = 0.3f;
  }
  const std::vector<PlacementRecord> records = records_of(placements);
  const cl::Buffer buffer = upload(records);
  const std::vector<LevelView> views{
      LevelView::look_at({1.5 * spacing, 4.0, 3.0}, {1.5 * spacing, 0.0, -3.0 * spacing}, {0, 1, 0},
                         50.0, kWidth, kHeight, 0.1, 60.0)};
  LevelChoiceOptions options;
  LevelChooser chooser(test::shared_context(), blub_levels(), count, options);
  chooser.set_occluders(walls);
  EXPECT_EQ(chooser.occluder_count(), walls.size());
  chooser.enqueue(buffer, count, views);
  const std::vector<int> with_walls = chooser.read().level_of;
  chooser.set_occluders({});
  chooser.forget();
  chooser.enqueue(buffer, count, views);
  const std::vector<int> without = chooser.read().level_of;
  const BodyBounds bounds = body_bounds(blub_levels().level(0).model);
  const std::vector<double> errors = level_errors(blub_levels());
  std::size_t hidden = 0, seen = 0, differ = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const int host = choose_level_on_host(records[i], bounds, errors, views, options, -1, walls);
    differ += with_walls[i] != host;
    if (without[i] >= 0) ++seen;
    if (without[i] >= 0 && with_walls[i] < 0) {
      ++hidden;
      // Hidden by a wall: the same as the host's test of some wall, in double.
      const glm::dvec3 centre = sphere_centre(placements[i], bounds);
      bool any = false;
      for (const WallOccluder& wall : walls) {
        any = any || wall_hides_sphere(views[0].eye(), centre,
                                       double(placements[i].length) * bounds.radius, wall);
      }
      EXPECT_TRUE(any) << "instance " << i;
    }
    if (with_walls[i] >= 0) {
      EXPECT_EQ(with_walls[i], without[i]) << "instance " << i;
    }
  }
  std::printf("%zu of %zu fish in view hidden by walls\n", hidden, seen);
  EXPECT_LE(differ, 3u);  // float's rounding at a wall's edge
  EXPECT_GT(hidden, seen / 10);
  EXPECT_LT(hidden, seen);
}

TEST(LevelChoice, FishPastALevelsRowsGoToTheNextCoarserLevelWithRoom) {
  const std::size_t count = 3000;
  const cl::Buffer buffer = upload(records_of(scattered(count, 7)));
  for (const std::vector<std::size_t>& rows :
       {std::vector<std::size_t>{5, 20, 60, 3000}, std::vector<std::size_t>{3, 3, 3, 40}}) {
    LevelChoiceOptions options;
    options.level_rows = rows;
    LevelChooser chooser(test::shared_context(), blub_levels(), count, options);
    std::size_t first = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(chooser.rows(k), rows[k]);
      EXPECT_EQ(chooser.list_first(k), first);
      first += rows[k];
    }
    chooser.enqueue(buffer, count, {camera()});
    const LevelChooser::Choice choice = chooser.read();
    const Placed expected = place_in_rows(choice.level_of, rows);
    EXPECT_EQ(choice.lists, expected.lists);
    EXPECT_EQ(choice.undrawn, expected.undrawn);
    for (std::size_t k = 0; k < rows.size(); ++k)
      EXPECT_EQ(choice.draw_arguments[5 * k + 1], expected.lists[k].size()) << "level " << k;
  }
  // The second rows hold fewer than the fish in view: some are drawn at no level.
  LevelChoiceOptions small;
  small.level_rows = {3, 3, 3, 40};
  LevelChooser chooser(test::shared_context(), blub_levels(), count, small);
  chooser.enqueue(buffer, count, {camera()});
  EXPECT_GT(chooser.read().undrawn, 0u);
}

TEST(LevelChoice, NoFishGoesBackAndForthInsideTheHysteresisBand) {
  // One fish straight ahead, its distance swinging by 2 % around where level 1's error
  // is the budget (well inside the 25 % band); a swing of 50 % moves it both ways.
  const std::vector<double> errors = level_errors(blub_levels());
  const double focal = double(kHeight) / (2.0 * std::tan(0.5 * glm::radians(kFov)));
  const double length = 0.4;
  const BodyBounds bounds = body_bounds(blub_levels().level(0).model);
  const double boundary = errors[1] * length * focal / 1.0 + length * bounds.radius;  // depth
  LevelChooser chooser(test::shared_context(), blub_levels(), 1);
  const auto level_at = [&](double depth) {
    Placement p;
    p.length = float(length);
    const glm::dvec3 at = kEye + depth * axes().forward;
    p.position = glm::vec3(at) - glm::vec3(double(p.length) * bounds.centre);
    chooser.enqueue(upload({placement_record(p)}), 1, {camera()});
    return chooser.read().level_of[0];
  };
  std::vector<int> small, large;
  for (int frame = 0; frame < 24; ++frame) {
    small.push_back(level_at(boundary * (1.0 + 0.02 * std::sin(0.7 * frame))));
  }
  // Going closer than the boundary forces the finer level once; back out inside the
  // band it stays: at most one change, never back.
  int changes = 0;
  for (std::size_t f = 1; f < small.size(); ++f) changes += small[f] != small[f - 1];
  EXPECT_LE(changes, 1) << "a level went back and forth inside the band";
  chooser.forget();
  for (int frame = 0; frame < 24; ++frame) {
    large.push_back(level_at(boundary * (1.0 + 0.5 * std::sin(0.7 * frame))));
  }
  int large_changes = 0;
  for (std::size_t f = 1; f < large.size(); ++f) large_changes += large[f] != large[f - 1];
  EXPECT_GE(large_changes, 2);
}

TEST(LevelChoice, TheBoundsHoldTheFishAtHalfItsLimits) {
  const RiggedMesh& model = blub();
  const BodyBounds bounds = body_bounds(model);
  const RigParameters values = test::at_fractions_of_the_limits(model, {0.5, -0.5});
  const DeformedBatch<double> bent = run_reference(model, values, NormalMode::kRotate);
  const BodyFrame& root = model.rig().components.front().frame;
  for (std::size_t i = 0; i < values.instance_count(); ++i) {
    for (std::size_t v = 0; v < model.vertex_count(); ++v) {
      // The reference leaves vertices in mesh coordinates: into the body-local frame.
      const glm::dvec3 local = root.point_to_local(bent.position(i, v));
      ASSERT_LE(glm::length(local - bounds.centre), bounds.radius) << i << " " << v;
    }
  }
}

std::string field_of(const std::function<void()>& step) {
  try {
    step();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
    return e.field();
  }
  return "accepted";
}

TEST(LevelChoice, BadInputIsNamedAndNothingIsEnqueued) {
  Context& context = test::shared_context();
  const DetailLevels& levels = blub_levels();
  LevelChoiceOptions options;
  options.pixel_budget = 0.0;
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "pixel_budget");
  options.pixel_budget = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "pixel_budget");
  options = LevelChoiceOptions{};
  options.hysteresis = 1.0;
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "hysteresis");
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 0); }), "capacity");
  options = LevelChoiceOptions{};
  options.level_rows = {4, 4, 4};
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "level_rows");
  options.level_rows = {4, 0, 4, 4};
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "level_rows[1]");
  options.level_rows = {4, 4, 5, 4};
  EXPECT_EQ(field_of([&] { LevelChooser(context, levels, 4, options); }), "level_rows[2]");

  LevelChooser chooser(context, levels, 4);
  const cl::Buffer four = upload(records_of(scattered(4, 1)));
  EXPECT_EQ(field_of([&] { chooser.enqueue(four, 5, {camera()}); }), "instances");
  const cl::Buffer two = upload(records_of(scattered(2, 1)));
  EXPECT_EQ(field_of([&] { chooser.enqueue(two, 3, {camera()}); }), "instances");
  EXPECT_EQ(field_of([&] { chooser.enqueue(four, 4, {}); }), "views");
  EXPECT_EQ(field_of([&] { chooser.enqueue(four, 4, std::vector<LevelView>(5, camera())); }),
            "views");
  LevelView squashed = camera();
  squashed.view_from_world[0][0] *= 2.0;
  EXPECT_EQ(field_of([&] {
              chooser.enqueue(four, 4, {camera(), squashed});
            }),
            "views[1].view_from_world");
  LevelView flat = camera();
  flat.clip_from_view = glm::dmat4(1.0);  // orthographic: no perspective
  EXPECT_EQ(field_of([&] { chooser.enqueue(four, 4, {flat}); }), "views[0].clip_from_view");
  LevelView blind = camera();
  blind.focal_pixels = 0.0;
  EXPECT_EQ(field_of([&] { chooser.enqueue(four, 4, {blind}); }), "views[0].focal_pixels");
  EXPECT_EQ(field_of([&] {
              (void)LevelView::look_at(kEye, kTarget, {0, 1, 0}, 0.0, kWidth, kHeight, kNear, kFar);
            }),
            "vertical_fov_degrees");
  EXPECT_EQ(field_of([&] {
              (void)LevelView::look_at(kEye, kTarget, {0, 1, 0}, kFov, kWidth, kHeight, 0.0, kFar);
            }),
            "view.clip_from_view");
  // A bad wall: named, and the walls stay as they were (none).
  EXPECT_EQ(
      field_of([&] {
        chooser.set_occluders({{{0.0, 0.0, 0.0}, 1.0, 1.0, 96}, {{0.0, 0.0, 0.0}, 0.0, 1.0, 96}});
      }),
      "occluders[1].radius");
  EXPECT_EQ(chooser.occluder_count(), 0u);
  // Nothing was chosen: every list is empty.
  const LevelChooser::Choice nothing = chooser.read();
  for (const std::vector<std::uint32_t>& list : nothing.lists) EXPECT_TRUE(list.empty());
}

}  // namespace
}  // namespace finflex

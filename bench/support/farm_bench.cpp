#include "farm_bench.hpp"

#include <algorithm>
#include <vector>

#include "swim_scene.hpp"
#include "timing.hpp"

namespace finflex::bench {
namespace {

constexpr double kFrameSeconds = 1.0 / 30.0;
constexpr std::size_t kRecordedSteps = 16;  // replayed in turn

// One scene's frames: device seconds per frame, each kernel's and, with levels, the
// level choice's.
struct SceneTimes {
  std::vector<double> frame, choice;
  std::vector<std::vector<double>> kernels;
};

// Enqueues the scene's frame of recorded step `step` and waits for it: the frame's
// device time, and the level choice's three kernels' (after each species' driver).
void time_frame(tank::SwimScene& scene, const std::vector<std::vector<SwimInput>>& step,
                SceneTimes& times) {
  const tank::FrameWork work = scene.enqueue_frame(
      kFrameSeconds,
      [&step](std::size_t s, SwimInput* staged) {
        std::copy(step[s].begin(), step[s].end(), staged);
      },
      true);
  times.frame.push_back(span_seconds(work.kernels.front(), work.kernels.back()));
  times.kernels.resize(work.kernels.size());
  for (std::size_t k = 0; k < work.kernels.size(); ++k)
    times.kernels[k].push_back(event_seconds(work.kernels[k]));
  if (scene.has_levels()) times.choice.push_back(span_seconds(work.kernels[1], work.kernels[3]));
}

nlohmann::ordered_json scene_record(const SceneTimes& times, std::size_t vertices) {
  nlohmann::ordered_json out;
  out["frame_seconds_median"] = median(times.frame);
  out["frame_seconds_min"] = *std::min_element(times.frame.begin(), times.frame.end());
  out["frame_seconds_max"] = *std::max_element(times.frame.begin(), times.frame.end());
  out["vertices_per_frame"] = vertices;
  out["vertices_per_second"] = double(vertices) / median(times.frame);
  nlohmann::ordered_json kernels = nlohmann::ordered_json::array();
  for (const std::vector<double>& kernel : times.kernels) kernels.push_back(median(kernel));
  out["kernel_seconds_median"] = kernels;
  return out;
}

}  // namespace

LevelView farm_camera(const tank::Hall& hall, int width, int height) {
  const tank::HallCamera c = tank::hall_camera(hall.hall_settings());
  return LevelView::look_at(c.eye, c.target, c.up, c.vertical_fov_degrees, width, height,
                            c.near_plane, c.far_plane);
}

nlohmann::ordered_json measure_farm(Context& context, const std::string& mesh,
                                    const std::string& rig, const FarmSettings& settings) {
  if (settings.frames == 0) {
    throw Error(ErrorCode::kInvalidArgument, "frames", "frames: at least one is needed");
  }
  const tank::HallSettings hall = tank::HallSettings::farm(settings.tanks, settings.fish);
  const std::vector<tank::SpeciesFiles> species{{mesh, rig}};
  tank::SwimScene leveled(
      context, species, settings.fish, hall, 1, settings.normals, settings.format, {}, {},
      tank::SceneLevels{settings.levels, settings.choice, settings.wall_occlusion});
  const LevelView camera = farm_camera(leveled.hall(), settings.width, settings.height);
  leveled.set_views({camera});
  tank::SwimScene full(context, species, settings.fish, hall, 1, settings.normals, settings.format);

  // The hall's steps, recorded from the leveled scene's hall (both halls are the same).
  std::vector<std::vector<std::vector<SwimInput>>> steps(kRecordedSteps);
  for (auto& step : steps) {
    leveled.hall().step(kFrameSeconds);
    step.resize(1);
    leveled.hall().inputs(0, step[0]);
  }
  SceneTimes with_levels, at_full_detail;
  SceneTimes warm_up;
  time_frame(leveled, steps[0], warm_up);  // PoCL compiles per work-group shape
  time_frame(full, steps[0], warm_up);
  for (std::size_t f = 0; f < settings.frames; ++f) {
    const auto& step = steps[(f + 1) % steps.size()];
    time_frame(leveled, step, with_levels);
    time_frame(full, step, at_full_detail);
  }

  nlohmann::ordered_json out;
  const DeviceDescription& device = context.description();
  out["device"] = device.device_name;
  out["platform"] = device.platform_name;
  out["mesh"] = mesh;
  out["fish"] = settings.fish;
  out["tanks"] = leveled.hall().tank_count();
  out["tank_diameter_m"] = hall.tank.diameter;
  out["tank_depth_m"] = hall.tank.depth;
  out["image"] = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  out["pixel_budget"] = settings.choice.pixel_budget;
  out["wall_occlusion"] = settings.wall_occlusion;
  out["frames"] = settings.frames;
  const tank::SwimScene::LevelCounts counts = leveled.level_counts(0);
  const DetailLevels& levels = leveled.species().front().leveled->levels;
  nlohmann::ordered_json per_level = nlohmann::ordered_json::array();
  std::size_t drawn = 0;
  for (std::size_t k = 0; k < counts.per_level.size(); ++k) {
    per_level.push_back({{"vertices", levels.level(k).vertex_count},
                         {"triangles", levels.level(k).triangle_count},
                         {"fins_frozen", levels.level(k).fins_frozen},
                         {"rows", leveled.species().front().leveled->deformer->chooser().rows(k)},
                         {"fish", counts.per_level[k]}});
    drawn += counts.per_level[k];
  }
  out["levels"] = per_level;
  out["fish_drawn"] = drawn;
  out["fish_demoted_for_rows"] = counts.demoted;
  out["fish_in_view_without_rows"] = counts.undrawn;
  nlohmann::ordered_json with = scene_record(with_levels, leveled.vertices_per_frame());
  with["level_choice_seconds_median"] = median(with_levels.choice);
  with["level_choice_share"] = median(with_levels.choice) / median(with_levels.frame);
  out["with_levels"] = with;
  out["full_detail"] = scene_record(at_full_detail, full.vertices_per_frame());
  out["speedup"] = median(at_full_detail.frame) / median(with_levels.frame);
  return out;
}

}  // namespace finflex::bench

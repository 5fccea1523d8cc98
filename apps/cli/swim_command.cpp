// finflex swim: a virtual RAS tank of swimming fish (apps/tank/), deformed every frame
// on an OpenCL device: the tank steps on the host, each species' swim driver and
// deformation run on the device, outputs in world space. With --out (or --render) every
// frame is also drawn (apps/pictures/, apps/render/) and written as PNG frames and a
// video, and with --annotate as a machine-vision dataset.
//
//   finflex swim [--fish N] [--seconds S] [--fps F] [--species MESH:RIG ...]
//                [--tank DIAMETER,DEPTH] [--tanks N] [--seed N] [--normals rotate|jacobian]
//                [--device NAME] [--out DIR [--mesh-frames LIST]]
//                [--size WxH] [--camera above|oblique|side|underwater] [--stereo B]
//                [--samples N]
//                [--distortion K1,K2,P1,P2,K3] [--noise READ,SHOT]
//                [--water clear|ras|turbid] [--turbidity NTU] [--dissolved A440] [--vary-optics]
//                [--refraction] [--port DISTANCE,THICKNESS,INDEX]
//                [--image-frames all|none|LIST] [--video auto|none|mp4,gif,apng]
//                [--annotate [--formats coco,yolo,webdataset] [--depth] [--keypoints LIST]]
//                [--render | --no-render] [--draw all|written]
//                [--hand-off auto|external-memory|shared|copy] [--reference-draw]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "finflex/gl_outputs.hpp"
#include "level_flags.hpp"
#include "staging_folder.hpp"
#include "swim_pictures.hpp"
#include "swim_plan.hpp"
#include "swim_scene.hpp"
#include "tank_pictures.hpp"
#include "timing.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

// The whole tank of one frame as one mesh (world space; positions and normals).
Mesh tank_mesh(tank::SwimScene& scene) {
  Mesh all;
  for (tank::Species& species : scene.species()) {
    if (!species.driver) continue;
    const tank::BatchReading reading(species);
    const DeformedBatch<float> batch = species.deformer->read(species.batch());
    Mesh rest = species.swim.model().mesh();
    rest.tangents.clear();
    rest.texcoords.clear();
    rest.groups.clear();
    for (std::size_t i = 0; i < batch.shape.instance_count; ++i) {
      const Mesh fish = instance_mesh(rest, batch, i);
      const auto base = static_cast<std::uint32_t>(all.positions.size());
      all.positions.insert(all.positions.end(), fish.positions.begin(), fish.positions.end());
      all.normals.insert(all.normals.end(), fish.normals.begin(), fish.normals.end());
      for (std::uint32_t index : fish.indices) all.indices.push_back(base + index);
    }
  }
  return all;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw Error(ErrorCode::kIo, "--out", "'" + path.string() + "': write failed");
}

void progress(std::size_t done, std::size_t total) {
  if (!isatty(STDERR_FILENO)) return;
  const int width = 40;
  const int filled = int(double(width) * double(done) / double(total));
  std::fprintf(stderr, "\r[%s%s] %3d%% frame %zu/%zu",
               std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(width - filled), ' ').c_str(),
               int(100.0 * double(done) / double(total)), done, total);
  if (done == total) std::fprintf(stderr, "\n");
}

// Per frame, seconds of each step (frames after the first, whose kernels and shaders
// are built on first use): the simulation's and deformation's of every frame, the
// rest (from draw on) of the frames drawn.
struct FrameTimes {
  std::vector<double> simulation, enqueue, kernels, wait, hand_off, draw, draw_gpu, reference_gpu,
      id_gpu, read_back, files, annotation, total;
  std::vector<double> cpu;  // CPU time of every thread of the process (not ffmpeg's)
};

// CPU seconds the process has used, all its threads (PoCL's and llvmpipe's included).
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (double v : values) total += v;
  return total;
}

double mean(const std::vector<double>& values) {
  return values.empty() ? 0.0 : sum(values) / double(values.size());
}

// The summary line's words on the hand-off: how it runs, and why not faster.
std::string hand_off_line(const pictures::HandOff& hand_off,
                          const pictures::TankPictures& pictures) {
  switch (hand_off.path) {
    case pictures::HandOffPath::kExternal:
      return std::string("Vulkan memory of ") + hand_off.device->name() + ", " +
             to_string(hand_off.import) + " by OpenCL, imported by GL; " +
             (pictures.device_ordered()
                  ? std::string("semaphores order the frame on the device")
                  : "waited for on the host: " + pictures.why_not_device_ordered());
    case pictures::HandOffPath::kShared:
      return "OpenCL writes the GL buffers: acquire, kernels, release; no external memory: " +
             hand_off.why_not_external;
    case pictures::HandOffPath::kCopy:
      break;
  }
  return "read back and glBufferSubData; no external memory: " + hand_off.why_not_external +
         "; no sharing: " + hand_off.why_not_shared;
}

nlohmann::ordered_json rendering_summary(const SwimPlan& plan, pictures::TankPictures& pictures,
                                         const pictures::HandOff& hand_off, const FrameTimes& t,
                                         double frames_per_second) {
  const render::DeviceInfo& device = pictures.renderer().device();
  const double frame = mean(t.total);
  const double deform = mean(t.simulation) + mean(t.enqueue) + mean(t.wait);
  nlohmann::ordered_json out;
  out["width"] = plan.pictures.width;
  out["height"] = plan.pictures.height;
  out["samples"] = device.samples;
  out["camera"] = pictures::to_string(plan.pictures.view);
  out["gl_renderer"] = device.gl_renderer;
  out["egl_display"] = device.egl_display;
  out["frames_per_second"] = frames_per_second;
  out["hand_off"] = {{"path", to_string(hand_off.path)},
                     {"seconds_per_frame_mean", mean(t.hand_off)}};
  if (hand_off.path == pictures::HandOffPath::kExternal) {
    out["hand_off"]["vulkan_device"] = hand_off.device->name();
    out["hand_off"]["import"] = to_string(hand_off.import);
    out["hand_off"]["ordered_on_the_device"] = pictures.device_ordered();
    if (!pictures.device_ordered())
      out["hand_off"]["why_not_ordered_on_the_device"] = pictures.why_not_device_ordered();
  }
  if (!hand_off.why_not_external.empty())
    out["hand_off"]["why_not_external"] = hand_off.why_not_external;
  if (!hand_off.why_not_shared.empty()) out["hand_off"]["why_not_shared"] = hand_off.why_not_shared;
  out["seconds_per_frame_mean"] = {{"frame", frame},
                                   {"deform", deform},
                                   {"simulation", mean(t.simulation)},
                                   {"upload_and_launch", mean(t.enqueue)},
                                   {"waiting_for_the_device", mean(t.wait)},
                                   {"kernels_on_the_device", mean(t.kernels)},
                                   {"hand_off", mean(t.hand_off)},
                                   {"draw", mean(t.draw)},
                                   {"draw_on_the_gpu", mean(t.draw_gpu)},
                                   {"read_back", mean(t.read_back)},
                                   {"files", mean(t.files)},
                                   {"annotation", mean(t.annotation)}};
  if (plan.files.annotate) {
    // The id pass (the masks' instance ids and depth), GPU time beside the draw's.
    out["seconds_per_frame_mean"]["id_pass_on_the_gpu"] = mean(t.id_gpu);
  }
  if (plan.reference_draw) {
    // The same triangles drawn the cheapest way (Renderer::render_reference), GPU
    // times of the same frames: the draw's distance from the geometry rate.
    out["reference_draw"] = {{"seconds_on_the_gpu_mean", mean(t.reference_gpu)},
                             {"draw_over_reference", mean(t.draw_gpu) / mean(t.reference_gpu)}};
  }
  out["cpu_seconds_per_frame_mean"] = mean(t.cpu);
  out["share_of_frame"] = {
      {"deform", deform / frame},       {"hand_off", mean(t.hand_off) / frame},
      {"draw", mean(t.draw) / frame},   {"read_back", mean(t.read_back) / frame},
      {"files", mean(t.files) / frame}, {"annotation", mean(t.annotation) / frame}};
  return out;
}

int run_swim(const SwimOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  try {
    const SwimPlan plan = plan_of(options);
    // With rendering, the renderer first (before any file: without EGL the command
    // stops here), then an OpenCL context sharing its GL context where the platform
    // can, so each species' deformation writes the GL buffers that are drawn.
    std::unique_ptr<render::Renderer> renderer;
    std::unique_ptr<Context> opencl;
    pictures::HandOff hand_off;
    if (plan.render) {
      renderer = std::make_unique<render::Renderer>(pictures::render_settings(plan.pictures));
      GlSharingContext shared =
          make_gl_sharing_context(options.device, renderer->egl_display(), renderer->egl_context());
      opencl = std::move(shared.context);
      hand_off = pictures::choose_hand_off(*renderer, *opencl, shared.why_not, plan.hand_off);
    } else {
      opencl = std::make_unique<Context>(options.device);
    }
    Context& context = *opencl;
    tank::SwimScene scene(
        context, plan.species, plan.fish, plan.hall, plan.seed, plan.normals,
        NormalFormat::kFloat32, {},
        renderer ? pictures::gl_outputs(*renderer, hand_off) : tank::OutputsFactory(), plan.levels);
    if (plan.levels && !renderer) {  // the pictures' camera chooses, drawn or not
      const render::Camera camera = pictures::hall_view_camera(
          plan.hall, plan.pictures.view, plan.pictures.width, plan.pictures.height);
      scene.set_views({LevelView::look_at(
          camera.position, camera.target, camera.up, camera.vertical_fov_degrees,
          plan.pictures.width, plan.pictures.height, camera.near_plane, camera.far_plane)});
    }
    std::unique_ptr<pictures::TankPictures> pictures;
    if (renderer) {
      pictures = std::make_unique<pictures::TankPictures>(*renderer, scene, plan.pictures);
    }
    std::unique_ptr<StagingFolder> staging;
    if (!options.out.empty()) staging = std::make_unique<StagingFolder>(options.out, "--out");
    const fs::path folder = staging ? fs::path(staging->path()) : fs::path();

    nlohmann::ordered_json info = {
        {"description", "FinFlex virtual RAS tank (finflex swim)"},
        {"fish", plan.fish},
        {"seed", plan.seed},
        {"fps", plan.fps},
        {"tank", {{"diameter_m", plan.hall.tank.diameter}, {"depth_m", plan.hall.tank.depth}}},
        {"tanks", plan.hall.tanks},
        {"vary_optics", plan.pictures.optics.vary},
        {"refraction", render::to_string(plan.pictures.refraction)}};
    std::unique_ptr<SwimPictureFiles> files;
    if (pictures && staging) {
      files =
          std::make_unique<SwimPictureFiles>(folder.string(), *pictures, scene, plan.files, info);
    }

    const double dt = 1.0 / plan.fps;
    FrameTimes t;
    // The tracks of summary.json (with --out): once a simulated second, every fish's
    // time, position, yaw and speed, kept as numbers until the summary is written.
    const bool tracked = !options.out.empty();
    constexpr std::size_t kTrackColumns = 6;
    std::vector<double> track_samples;  // per tracked frame, per fish, kTrackColumns
    const std::size_t track_every = std::max<std::size_t>(1, std::size_t(std::lround(plan.fps)));
    const auto start = Clock::now();
    Clock::time_point timed_start = start;
    std::size_t timed_frames = 0;  // after the first, drawn or not
    double first_frame = 0.0;
    std::vector<std::pair<cl::Event, cl::Event>> kernel_spans;  // per timed frame
    // Drawn, the next frame's hall steps on a thread while this frame is drawn (nothing
    // of the draw reads the hall), unless the annotations read this frame's fish.
    const bool step_ahead = pictures && !plan.files.annotate;
    std::future<double> next_step;  // its seconds
    for (std::size_t f = 0; f < plan.frames; ++f) {
      const auto frame_start = Clock::now();
      const double cpu_start = process_cpu_seconds();
      const double step_seconds = next_step.valid() ? next_step.get() : scene.step_hall(dt);
      tank::FrameWork work = scene.enqueue_stepped_frame(dt, true);
      work.simulation_seconds += step_seconds;
      const double time = scene.hall().time();
      if (tracked && f % track_every == 0) {
        for (const tank::Fish& fish : scene.hall().fish()) {
          track_samples.insert(track_samples.end(), {time, fish.position.x, fish.position.y,
                                                     fish.position.z, fish.yaw, fish.speed});
        }
      }
      if (step_ahead && f + 1 < plan.frames) {
        next_step = std::async(std::launch::async, [&scene, dt] { return scene.step_hall(dt); });
      }
      Clock::time_point step = Clock::now();
      // Drawn, the frame orders itself (fish_hand_off.hpp) and nothing waits for the
      // device here; else the loop's frame is the deformation's.
      if (!pictures) context.queue().finish();
      const double wait = seconds_since(step);
      double draw = 0.0;
      double draw_gpu = 0.0;
      double reference_gpu = 0.0;
      double id_gpu = 0.0;
      PictureFileTimes file_times;
      // With --draw written a frame that writes nothing (a dataset shard's warm-up
      // before its first image) is simulated and deformed, not drawn; the first frame is
      // drawn all the same, so that the shaders are built where the kernels are.
      const bool drawn = pictures && (f == 0 || !plan.draw_written || plan.files.writes(f));
      if (drawn) {
        step = Clock::now();
        pictures->set_frame(f);
        pictures->draw();
        draw = seconds_since(step);
        draw_gpu = pictures->renderer().gpu_draw_seconds();
        if (plan.reference_draw) {
          pictures->draw_reference();
          reference_gpu = pictures->renderer().gpu_reference_seconds();
        }
        if (files) file_times = files->add_frame(f, time);
        if (files && plan.files.annotate) id_gpu = pictures->renderer().gpu_id_seconds();
      }
      if (f == 0) {
        // Kernels (PoCL per work-group shape) and shaders are built on the first frame.
        first_frame = seconds_since(frame_start);
        timed_start = Clock::now();
      } else {
        ++timed_frames;
        t.simulation.push_back(work.simulation_seconds);
        t.enqueue.push_back(work.enqueue_seconds);
        // Read once the loop is done: reading now would wait for the device.
        kernel_spans.emplace_back(work.kernels.front(), work.kernels.back());
        t.wait.push_back(wait);
        t.hand_off.push_back(work.handoff_seconds);
      }
      if (f > 0 && (drawn || !pictures)) {  // the frame's steps, of the frames drawn
        t.draw.push_back(draw);
        t.draw_gpu.push_back(draw_gpu);
        t.reference_gpu.push_back(reference_gpu);
        t.id_gpu.push_back(id_gpu);
        t.read_back.push_back(file_times.read_back);
        t.files.push_back(file_times.files);
        t.annotation.push_back(file_times.annotation);
        t.total.push_back(seconds_since(frame_start));
        t.cpu.push_back(process_cpu_seconds() - cpu_start);
      }
      if (plan.mesh_frames.count(f)) {
        char name[64];
        std::snprintf(name, sizeof name, "tank_frame_%06zu.glb", f);
        save_mesh((folder / name).string(), tank_mesh(scene));
      }
      progress(f + 1, plan.frames);
    }
    // The timed frames end when the GPU has drawn the last one: nothing waits for it in
    // the loop where semaphores order the frames.
    if (pictures) pictures->renderer().finish();
    const double timed_span = seconds_since(timed_start);
    if (files) files->finish();  // the frames still in flight, and the pool's work
    const double wall = seconds_since(start);
    for (const auto& [first, last] : kernel_spans)
      t.kernels.push_back(bench::span_seconds(first, last));
    const double timed_fps = timed_frames == 0 ? 0.0 : double(timed_frames) / timed_span;
    const double vertices = double(scene.vertices_per_frame());
    const double kernel_median = t.kernels.empty() ? 0.0 : bench::median(t.kernels);
    std::string census;
    for (const tank::Species& species : scene.species()) {
      census += (census.empty() ? "" : ", ") +
                std::to_string(species.driver ? species.driver->fish_count() : 0) + " " +
                species.name;
    }
    const std::string tanks =
        plan.hall.tanks == 1 ? "tank" : std::to_string(plan.hall.tanks) + " tanks";
    std::printf(
        "swam %zu fish (%s) for %.3g s at %.3g fps (%zu frames) in %s %.3g m x %.3g m %s on %s\n",
        plan.fish, census.c_str(), double(plan.frames) / plan.fps, plan.fps, plan.frames,
        plan.hall.tanks == 1 ? "a" : "a hall of", plan.hall.tank.diameter, plan.hall.tank.depth,
        tanks.c_str(), context.description().device_name.c_str());
    std::printf(
        "  %.3g M vertices per frame; %.1f frames/s overall (first frame %.2f s with kernel "
        "builds)\n",
        vertices * 1e-6, double(plan.frames) / wall, first_frame);
    for (std::size_t s = 0; s < scene.species().size(); ++s) {
      if (!scene.species()[s].leveled) continue;
      const tank::SwimScene::LevelCounts counts = scene.level_counts(s);
      std::string per_level;
      for (std::size_t n : counts.per_level)
        per_level += (per_level.empty() ? "" : "/") + std::to_string(n);
      std::printf(
          "  %s at levels 0..%zu (last frame): %s fish, %zu culled or in no level's rows\n",
          scene.species()[s].name.c_str(), counts.per_level.size() - 1, per_level.c_str(),
          scene.species()[s].driver->fish_count() -
              std::accumulate(counts.per_level.begin(), counts.per_level.end(), std::size_t{0}));
    }
    if (!t.kernels.empty()) {
      std::printf(
          "  per frame (median): simulation %.3f ms, upload and launch %.3f ms (host), kernels "
          "%.3f ms (device): %.3g G vertices/s\n",
          bench::median(t.simulation) * 1e3, bench::median(t.enqueue) * 1e3, kernel_median * 1e3,
          vertices / kernel_median * 1e-9);
    }
    nlohmann::ordered_json rendering;
    if (pictures && !t.total.empty()) {
      rendering = rendering_summary(plan, *pictures, hand_off, t, timed_fps);
      const auto& ms = rendering["seconds_per_frame_mean"];
      const auto& share = rendering["share_of_frame"];
      const auto part = [&](const char* name) {
        char text[64];
        std::snprintf(text, sizeof text, "%s %.1f ms (%.0f %%)", name, ms[name].get<double>() * 1e3,
                      share[name].get<double>() * 100.0);
        return std::string(text);
      };
      std::printf("  rendered %dx%d, %dx multisampling, %s camera, on %s: %.2f frames/s\n",
                  plan.pictures.width, plan.pictures.height, pictures->renderer().device().samples,
                  pictures::to_string(plan.pictures.view),
                  pictures->renderer().device().gl_renderer.c_str(), timed_fps);
      std::printf(
          "  a drawn frame (mean of %zu): %.1f ms (CPU time %.1f ms): %s, %s, %s, %s, %s, %s; "
          "the draw on the GPU %.1f ms\n",
          t.total.size(), ms["frame"].get<double>() * 1e3,
          rendering["cpu_seconds_per_frame_mean"].get<double>() * 1e3, part("deform").c_str(),
          part("hand_off").c_str(), part("draw").c_str(), part("read_back").c_str(),
          part("files").c_str(), part("annotation").c_str(), mean(t.draw_gpu) * 1e3);
      if (plan.files.annotate) {
        std::printf("  the id pass on the GPU %.1f ms\n", mean(t.id_gpu) * 1e3);
      }
      if (plan.reference_draw) {
        std::printf(
            "  the reference draw (the same triangles, pass-through) on the GPU %.1f ms: "
            "the draw is %.2f times it\n",
            mean(t.reference_gpu) * 1e3, mean(t.draw_gpu) / mean(t.reference_gpu));
      }
      std::printf("  hand-off: %s (%s), %.2f ms a frame\n", to_string(hand_off.path),
                  hand_off_line(hand_off, *pictures).c_str(), mean(t.hand_off) * 1e3);
    }
    if (files) {
      std::printf("  wrote %zu frame images, %zu videos%s\n", files->images_written(),
                  plan.files.videos.size(),
                  plan.files.annotate
                      ? (", " + std::to_string(files->annotations()) + " annotations").c_str()
                      : "");
    }
    std::printf(
        "  fish put back inside the water by the tank: %zu times; braking in front of a "
        "boundary: %zu fish-steps\n",
        scene.hall().corrections(), scene.hall().brakes());
    if (staging) {
      nlohmann::ordered_json summary;
      summary["device"] = context.description().device_name;
      summary["fish"] = plan.fish;
      summary["frames"] = plan.frames;
      summary["fps"] = plan.fps;
      summary["seed"] = plan.seed;
      summary["tank"] = {{"diameter_m", plan.hall.tank.diameter},
                         {"depth_m", plan.hall.tank.depth},
                         {"wall_current_m_per_s", plan.hall.tank.wall_current}};
      summary["tanks"] = plan.hall.tanks;
      summary["vertices_per_frame"] = scene.vertices_per_frame();
      summary["seconds_per_frame_median"] = {
          {"simulation", t.simulation.empty() ? 0.0 : bench::median(t.simulation)},
          {"upload_and_launch", t.enqueue.empty() ? 0.0 : bench::median(t.enqueue)},
          {"kernels", kernel_median}};
      if (!rendering.is_null()) summary["rendering"] = rendering;
      summary["first_frame_seconds"] = first_frame;
      summary["wall_seconds"] = wall;
      summary["corrections"] = scene.hall().corrections();
      summary["brakes"] = scene.hall().brakes();
      summary["track_columns"] = {"time_s", "x_m", "y_m", "z_m", "yaw_rad", "speed_m_per_s"};
      const std::vector<tank::Fish>& fish = scene.hall().fish();
      nlohmann::ordered_json tracks = nlohmann::ordered_json::array();
      for (std::size_t i = 0; i < fish.size(); ++i) {
        nlohmann::ordered_json samples = nlohmann::ordered_json::array();
        for (std::size_t at = i * kTrackColumns; at < track_samples.size();
             at += fish.size() * kTrackColumns) {
          samples.push_back(
              std::vector<double>(track_samples.begin() + std::ptrdiff_t(at),
                                  track_samples.begin() + std::ptrdiff_t(at + kTrackColumns)));
        }
        tracks.push_back({{"species", scene.species()[fish[i].species].name},
                          {"length_m", fish[i].length},
                          {"samples", std::move(samples)}});
      }
      summary["tracks"] = tracks;
      write_text(folder / "summary.json", summary.dump(1) + "\n");
      staging->commit();
      std::printf("  wrote %s\n", options.out.c_str());
    }
    return kExitSuccess;
  } catch (const std::exception& error) {
    if (isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
    return fail("swim", error.what());
  }
}

}  // namespace

Command add_swim_command(CLI::App& app) {
  auto options = std::make_shared<SwimOptions>();
  CLI::App* swim = app.add_subcommand("swim", "Fish swimming in a virtual RAS tank");
  swim->add_option("--fish", options->fish, "Fish in the tank")->capture_default_str();
  swim->add_option("--seconds", options->seconds, "Simulated seconds")->capture_default_str();
  swim->add_option("--fps", options->fps, "Frames per simulated second")->capture_default_str();
  swim->add_option("--species", options->species,
                   "MESH:RIG, a mesh and its swim rig (repeatable; default: the bundled fish)")
      ->allow_extra_args(false);
  swim->add_option("--tank", options->tank, "DIAMETER,DEPTH in metres (default 3.66,1.22)");
  swim->add_option("--tanks", options->tanks,
                   "A farm hall of N tanks in rows of 4, each holding 1,000 fish or more at the "
                   "default tank's density unless --tank sizes them; seen down the hall")
      ->capture_default_str();
  swim->add_option("--seed", options->seed, "Random seed of the tank")->capture_default_str();
  swim->add_option("--normals", options->normals, "rotate or jacobian")->capture_default_str();
  swim->add_option("--device", options->device,
                   "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  swim->add_option("--out", options->out,
                   "Folder for summary.json, the frames as PNGs and a video, camera.json "
                   "(and --mesh-frames, --annotate)");
  swim->add_option("--mesh-frames", options->mesh_frames,
                   "Frames to write as whole-tank meshes (e.g. 0,150,last)");
  swim->add_option("--size", options->size, "Rendered frames' size, WIDTHxHEIGHT")
      ->capture_default_str();
  swim->add_option("--camera", options->camera, "above, oblique, side or underwater")
      ->capture_default_str();
  swim->add_option("--stereo", options->stereo,
                   "BASELINE in metres: a rectified stereo pair, the right camera that far to "
                   "the right (frame_NNNNNN_right.png beside each image frame)");
  swim->add_option("--distortion", options->distortion,
                   "K1,K2,P1,P2,K3: the image frames' lens distortion in OpenCV's model (masks, "
                   "depth and keypoints through the same lens)");
  swim->add_option("--noise", options->noise,
                   "READ,SHOT: the image frames' sensor noise, sigmas in sRGB levels (shot at "
                   "full scale), seeded by --seed");
  swim->add_option("--water", options->water,
                   std::string("The tank's water: ") + pictures::water_type_names())
      ->capture_default_str();
  swim->add_option("--turbidity", options->turbidity,
                   "The water's turbidity in NTU, 0..100 (default: the water type's)");
  swim->add_option("--dissolved", options->dissolved,
                   "The water's dissolved organic matter: its absorption at 440 nm per metre, "
                   "0..20 (default: the water type's)");
  swim->add_flag("--vary-optics", options->vary_optics,
                 "Each frame its own water and light, drawn from the documented ranges "
                 "(seeded by --seed)");
  swim->add_flag("--refraction", options->refraction,
                 "The view rays bend at the water surface, or at the underwater camera's flat "
                 "port (Snell's law per vertex; masks, depth and keypoints where the camera "
                 "sees them)");
  swim->add_option("--port", options->port,
                   "DISTANCE,THICKNESS,INDEX: the underwater camera's flat port, metres from "
                   "the lens to the window, its thickness in metres and refractive index "
                   "(default 0.02,0.01,1.49: acrylic)");
  swim->add_option("--samples", options->samples, "Multisampling of the rendered frames, 1..16")
      ->capture_default_str();
  swim->add_option("--image-frames", options->image_frames,
                   "Frames written as PNGs: all (default), none, or a list (0,150,last)");
  swim->add_option("--video", options->video,
                   "auto (MP4 with ffmpeg, else APNG; default), none, or a list of mp4, gif, apng");
  swim->add_flag("--annotate", options->annotate,
                 "Also instance masks and COCO annotations of the image frames");
  swim->add_option("--formats", options->formats,
                   "With --annotate: the dataset's formats, coco, yolo (Ultralytics detect, "
                   "segment and pose) and webdataset (tar shards)")
      ->capture_default_str();
  swim->add_option("--keypoints", options->keypoints,
                   "With --annotate: the keypoints to annotate, a list of snout, tail_fork, "
                   "caudal_upper_tip, caudal_lower_tip, left_pectoral_tip, right_pectoral_tip "
                   "(default all)");
  swim->add_option("--length-weight", options->length_weights,
                   "SPECIES:A,B, with --annotate: that species' weights by W g = A (L cm)^B "
                   "(repeatable; default A 0.01, B 3)")
      ->allow_extra_args(false);
  swim->add_flag("--depth", options->depth,
                 "With --annotate: each frame's depth in metres (depth/frame_NNNNNN.npy)");
  swim->add_flag_function(
      "--render,!--no-render",
      [options](std::int64_t count) { options->render = count > 0 ? 1 : 0; },
      "Draw every frame (default with --out); without --out only the timing is printed");
  swim->add_option("--draw", options->draw,
                   "all: draw every frame; written: only the frames written as images or "
                   "video (and the first), the others simulated and deformed")
      ->capture_default_str();
  swim->add_option("--hand-off", options->hand_off,
                   "How the deformed fish reach the renderer: auto (the first that runs), "
                   "external-memory, shared or copy")
      ->capture_default_str();
  swim->add_option("--levels", options->levels,
                   "Levels of detail (1 to 8) with culling, chosen from the camera each frame "
                   "(default: every fish at full detail)");
  swim->add_flag(kFreezeFinsFlag, options->freeze_fins, kFreezeFinsHelp);
  swim->add_flag(kWallOcclusionFlag, options->wall_occlusion, kWallOcclusionHelp);
  swim->add_option("--pixel-budget", options->pixel_budget,
                   "With --levels: the error a level may show, in pixels")
      ->capture_default_str();
  swim->add_option("--triangle-ratio", options->triangle_ratio,
                   "With --levels: each level's share of the finer level's triangles")
      ->capture_default_str();
  swim->add_flag("--reference-draw", options->reference_draw,
                 "Each frame also the same triangles drawn the cheapest way, and both GPU times");
  return {[options] { plan_of(*options); }, [options] { return run_swim(*options); }};
}

}  // namespace finflex::cli

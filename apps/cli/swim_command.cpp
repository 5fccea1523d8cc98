// finflex swim: a virtual RAS tank of swimming fish (apps/tank/), deformed every frame
// on an OpenCL device: the tank steps on the host, each species' swim driver and
// deformation run on the device, outputs in world space.
//
//   finflex swim [--fish N] [--seconds S] [--fps F] [--species MESH:RIG ...]
//                [--tank DIAMETER,DEPTH] [--seed N] [--normals rotate|jacobian]
//                [--device NAME] [--out DIR [--mesh-frames LIST]]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "swim_scene.hpp"
#include "timing.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

struct SwimOptions {
  std::string fish = "1000";
  std::string seconds = "10";
  std::string fps = "30";
  std::vector<std::string> species;
  std::string tank;
  std::string seed = "1";
  std::string normals = "jacobian";
  std::string device;
  std::string out;
  std::string mesh_frames;
};

// What the command runs, every value checked.
struct SwimPlan {
  std::size_t fish = 0;
  std::size_t frames = 0;
  double fps = 0.0;
  std::vector<tank::SpeciesFiles> species;
  tank::TankSettings tank;
  std::uint64_t seed = 0;
  NormalMode normals = NormalMode::kJacobian;
  std::set<std::size_t> mesh_frames;
};

// "0,150,last": frame indices below `frames` ("last": the final frame).
std::set<std::size_t> parse_frames(const std::string& text, std::size_t frames) {
  std::set<std::size_t> chosen;
  std::size_t begin = 0;
  while (begin <= text.size() && !text.empty()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    chosen.insert(item == "last" ? frames - 1 : parse_count(item, "--mesh-frames", 0, frames - 1));
    begin = comma + 1;
  }
  return chosen;
}

// The output folder: an existing folder, or one whose parent exists (created later).
void check_out_folder(const std::string& out) {
  if (out.empty()) return;
  std::error_code ec;
  const fs::path path(out);
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) {
      throw Error(ErrorCode::kInvalidArgument, "--out", "--out '" + out + "' is not a folder");
    }
    if (access(out.c_str(), W_OK) != 0) {
      throw Error(ErrorCode::kIo, "--out", "--out '" + out + "': cannot write there");
    }
    return;
  }
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) {
    throw Error(ErrorCode::kIo, "--out",
                "--out '" + out + "': its parent folder '" + parent.string() + "' does not exist");
  }
}

SwimPlan plan_of(const SwimOptions& options) {
  SwimPlan plan;
  plan.fish = parse_count(options.fish, "--fish", 1, 1000000);
  const double seconds = parse_positive(options.seconds, "--seconds");
  plan.fps = parse_positive(options.fps, "--fps");
  const double frames = std::round(seconds * plan.fps);
  if (frames < 1.0 || frames > 1e7) {
    throw Error(ErrorCode::kInvalidArgument, "--seconds",
                "--seconds " + options.seconds + " at --fps " + options.fps + " gives " +
                    std::to_string(frames) + " frames (expected 1 to 10,000,000)");
  }
  plan.frames = static_cast<std::size_t>(frames);
  for (const std::string& text : options.species)
    plan.species.push_back(tank::parse_species(text, "--species"));
  if (plan.species.empty()) plan.species = tank::bundled_species(FINFLEX_DATA_DIR);
  for (const tank::SpeciesFiles& files : plan.species) {
    for (const std::string& path : {files.mesh, files.rig}) {
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) {
        throw Error(ErrorCode::kIo, "--species", "--species: '" + path + "' is not a file");
      }
    }
  }
  if (!options.tank.empty()) {
    const auto [diameter, depth] = parse_positive_pair(options.tank, "--tank");
    plan.tank.diameter = diameter;
    plan.tank.depth = depth;
  }
  plan.seed = parse_count(options.seed, "--seed", 0, UINT64_MAX);
  plan.normals = parse_normal_mode(options.normals, "--normals");
  if (!options.mesh_frames.empty() && options.out.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--mesh-frames", "--mesh-frames needs --out");
  }
  plan.mesh_frames = parse_frames(options.mesh_frames, plan.frames);
  check_out_folder(options.out);
  return plan;
}

// The whole tank of one frame as one mesh (world space; positions and normals).
Mesh tank_mesh(tank::SwimScene& scene) {
  Mesh all;
  for (tank::Species& species : scene.species()) {
    if (!species.driver) continue;
    const DeformedBatch<float> batch = species.deformer->read(species.batch);
    Mesh rest = species.swim.model().mesh();
    rest.tangents.clear();
    rest.texcoords.clear();
    rest.groups.clear();
    for (std::size_t i = 0; i < batch.layout.instance_count; ++i) {
      const Mesh fish = instance_mesh(rest, batch, i);
      const auto base = static_cast<std::uint32_t>(all.positions.size());
      all.positions.insert(all.positions.end(), fish.positions.begin(), fish.positions.end());
      all.normals.insert(all.normals.end(), fish.normals.begin(), fish.normals.end());
      for (std::uint32_t index : fish.indices) all.indices.push_back(base + index);
    }
  }
  return all;
}

// Writes `text` to `path` through a temporary name in the same folder.
void write_atomically(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out) throw Error(ErrorCode::kIo, "--out", "'" + temporary.string() + "': write failed");
  }
  fs::rename(temporary, path);
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

int run_swim(const SwimOptions& options) {
  try {
    const SwimPlan plan = plan_of(options);
    Context context(options.device);
    tank::SwimScene scene(context, plan.species, plan.fish, plan.tank, plan.seed, plan.normals);
    if (!options.out.empty()) fs::create_directories(options.out);

    const double dt = 1.0 / plan.fps;
    std::vector<double> simulation, enqueue, kernels;
    nlohmann::ordered_json tracks = nlohmann::ordered_json::array();
    for (const tank::Fish& fish : scene.tank().fish()) {
      tracks.push_back({{"species", scene.species()[fish.species].name},
                        {"length_m", fish.length},
                        {"samples", nlohmann::ordered_json::array()}});
    }
    const std::size_t track_every = std::max<std::size_t>(1, std::size_t(std::lround(plan.fps)));
    const auto start = std::chrono::steady_clock::now();
    double first_frame = 0.0;
    for (std::size_t f = 0; f < plan.frames; ++f) {
      const auto frame_start = std::chrono::steady_clock::now();
      const tank::FrameWork work = scene.enqueue_frame(dt, true);
      const double device = bench::span_seconds(work.kernels.front(), work.kernels.back());
      if (f == 0) {
        // Kernels are built on the first frame (PoCL per work-group shape): apart.
        first_frame =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - frame_start).count();
      } else {
        simulation.push_back(work.simulation_seconds);
        enqueue.push_back(work.enqueue_seconds);
        kernels.push_back(device);
      }
      if (f % track_every == 0) {
        const std::vector<tank::Fish>& fish = scene.tank().fish();
        for (std::size_t i = 0; i < fish.size(); ++i) {
          tracks[i]["samples"].push_back({scene.tank().time(), fish[i].position.x,
                                          fish[i].position.y, fish[i].position.z, fish[i].yaw,
                                          fish[i].speed});
        }
      }
      if (plan.mesh_frames.count(f)) {
        char name[64];
        std::snprintf(name, sizeof name, "tank_frame_%06zu.glb", f);
        save_mesh((fs::path(options.out) / name).string(), tank_mesh(scene));
      }
      progress(f + 1, plan.frames);
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double vertices = double(scene.vertices_per_frame());
    const double kernel_median = kernels.empty() ? 0.0 : bench::median(kernels);
    std::string census;
    for (const tank::Species& species : scene.species()) {
      census += (census.empty() ? "" : ", ") +
                std::to_string(species.driver ? species.driver->fish_count() : 0) + " " +
                species.name;
    }
    std::printf(
        "swam %zu fish (%s) for %.3g s at %.3g fps (%zu frames) in a %.3g m x %.3g m tank on %s\n",
        plan.fish, census.c_str(), double(plan.frames) / plan.fps, plan.fps, plan.frames,
        plan.tank.diameter, plan.tank.depth, context.description().device_name.c_str());
    std::printf(
        "  %.3g M vertices per frame; %.1f frames/s overall (first frame %.2f s with kernel "
        "builds)\n",
        vertices * 1e-6, double(plan.frames) / wall, first_frame);
    if (!kernels.empty()) {
      std::printf(
          "  per frame (median): simulation %.3f ms, upload and launch %.3f ms (host), kernels "
          "%.3f ms (device): %.3g G vertices/s\n",
          bench::median(simulation) * 1e3, bench::median(enqueue) * 1e3, kernel_median * 1e3,
          vertices / kernel_median * 1e-9);
    }
    std::printf("  fish put back inside the water by the tank: %zu times\n",
                scene.tank().corrections());
    if (!options.out.empty()) {
      nlohmann::ordered_json summary;
      summary["device"] = context.description().device_name;
      summary["fish"] = plan.fish;
      summary["frames"] = plan.frames;
      summary["fps"] = plan.fps;
      summary["seed"] = plan.seed;
      summary["tank"] = {{"diameter_m", plan.tank.diameter},
                         {"depth_m", plan.tank.depth},
                         {"wall_current_m_per_s", plan.tank.wall_current}};
      summary["vertices_per_frame"] = scene.vertices_per_frame();
      summary["seconds_per_frame_median"] = {{"simulation", bench::median(simulation)},
                                             {"upload_and_launch", bench::median(enqueue)},
                                             {"kernels", kernel_median}};
      summary["first_frame_seconds"] = first_frame;
      summary["wall_seconds"] = wall;
      summary["corrections"] = scene.tank().corrections();
      summary["track_columns"] = {"time_s", "x_m", "y_m", "z_m", "yaw_rad", "speed_m_per_s"};
      summary["tracks"] = tracks;
      write_atomically(fs::path(options.out) / "summary.json", summary.dump(1) + "\n");
      std::printf("  wrote %s\n", (fs::path(options.out) / "summary.json").string().c_str());
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
  swim->add_option("--seed", options->seed, "Random seed of the tank")->capture_default_str();
  swim->add_option("--normals", options->normals, "rotate or jacobian")->capture_default_str();
  swim->add_option("--device", options->device,
                   "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  swim->add_option("--out", options->out, "Folder for summary.json (and --mesh-frames)");
  swim->add_option("--mesh-frames", options->mesh_frames,
                   "Frames to write as whole-tank meshes (e.g. 0,150,last)");
  return [options] { return run_swim(*options); };
}

}  // namespace finflex::cli

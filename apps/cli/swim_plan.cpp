#include "swim_plan.hpp"

#include "level_flags.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "render/video.hpp"
#include "staging_folder.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

// "0,150,last": frame indices below `frames` ("last": the final frame).
std::set<std::size_t> parse_frames(const std::string& text, std::size_t frames,
                                   const std::string& option) {
  std::set<std::size_t> chosen;
  std::size_t begin = 0;
  while (begin <= text.size() && !text.empty()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    chosen.insert(item == "last" ? frames - 1 : parse_count(item, option, 0, frames - 1));
    begin = comma + 1;
  }
  return chosen;
}

// "auto": MP4 when ffmpeg is installed, else APNG; "none"; or a list of mp4, gif, apng.
// Returns the files' extensions ("png" for APNG). kInvalidArgument naming --video for
// an unknown name, kIo for MP4 or GIF without ffmpeg.
std::vector<std::string> parse_videos(const std::string& text) {
  if (text == "none") return {};
  if (text == "auto") return {render::ffmpeg_available() ? "mp4" : "png"};
  std::vector<std::string> videos;
  for (const std::string& item : split_list(text)) {
    if (item != "mp4" && item != "gif" && item != "apng") {
      throw Error(ErrorCode::kInvalidArgument, "--video",
                  "--video '" + text + "': '" + item +
                      "' is not a video format (auto, none, or a list of mp4, gif, apng)");
    }
    if (item != "apng" && !render::ffmpeg_available()) {
      throw Error(ErrorCode::kIo, "--video",
                  "--video " + item +
                      " needs the ffmpeg program, which is not on PATH "
                      "(--video apng writes an animated PNG)");
    }
    const std::string extension = item == "apng" ? "png" : item;
    if (std::find(videos.begin(), videos.end(), extension) == videos.end()) {
      videos.push_back(extension);
    }
  }
  return videos;
}

// The water and the light of the pictures.
void plan_optics(const SwimOptions& options, SwimPlan& plan) {
  pictures::OpticsSettings& optics = plan.pictures.optics;
  optics.base.water = pictures::water_type(options.water, "--water");
  if (!options.turbidity.empty()) {
    optics.base.water.turbidity_ntu =
        float(parse_in_range(options.turbidity, "--turbidity", 0.0, 100.0, "NTU"));
  }
  if (!options.dissolved.empty()) {
    optics.base.water.dissolved_absorption_440 =
        float(parse_in_range(options.dissolved, "--dissolved", 0.0, 20.0, "per metre"));
  }
  const pictures::CameraView view = plan.pictures.view;
  if (options.refraction && view == pictures::CameraView::kSide) {
    throw Error(ErrorCode::kInvalidArgument, "--refraction",
                "--refraction bends the view rays at the water surface or the underwater "
                "camera's port: the side camera looks through the wall (use --camera above, "
                "oblique or underwater)");
  }
  if (options.refraction) {
    plan.pictures.refraction = view == pictures::CameraView::kUnderwater
                                   ? render::ViewRefraction::kPort
                                   : render::ViewRefraction::kSurface;
  }
  if (!options.port.empty()) {
    if (plan.pictures.refraction != render::ViewRefraction::kPort) {
      throw Error(ErrorCode::kInvalidArgument, "--port",
                  "--port is the underwater camera's housing: it needs --camera underwater "
                  "--refraction");
    }
    const std::vector<double> port = parse_number_list(options.port, "--port", 3);
    const auto check = [&](double value, double low, double high, const char* what) {
      if (value < low || value > high) {
        throw Error(ErrorCode::kInvalidArgument, "--port",
                    "--port '" + options.port + "': " + what);
      }
    };
    check(port[0], 1e-4, 0.5, "the distance is 0.0001 to 0.5 m");
    check(port[1], 0.0, 0.1, "the thickness is 0 to 0.1 m");
    check(port[2], 1.0, 2.0, "the refractive index is 1 to 2");
    plan.pictures.port = {float(port[0]), float(port[1]), float(port[2])};
  }
  optics.vary = options.vary_optics;
  optics.seed = plan.seed;
  if (optics.vary) {
    for (const auto& [given, option] : {std::pair{!options.turbidity.empty(), "--turbidity"},
                                        std::pair{!options.dissolved.empty(), "--dissolved"}}) {
      if (given) {
        throw Error(ErrorCode::kInvalidArgument, option,
                    std::string(option) + " with --vary-optics: the water is drawn each frame");
      }
    }
  }
}

// The pictures' options, checked against each other and --out.
void plan_pictures(const SwimOptions& options, SwimPlan& plan) {
  const bool out = !options.out.empty();
  plan.render = options.render == 1 || (options.render == -1 && out);
  const auto [width, height] = parse_size(options.size, "--size");
  plan.pictures.width = width;
  plan.pictures.height = height;
  plan.pictures.view = pictures::parse_camera_view(options.camera, "--camera");
  if (!options.stereo.empty()) {
    const double baseline = parse_positive(options.stereo, "--stereo");
    if (baseline > 10.0) {
      throw Error(ErrorCode::kInvalidArgument, "--stereo",
                  "--stereo " + options.stereo + ": a baseline above 10 m");
    }
    if (!plan.render) {
      throw Error(ErrorCode::kInvalidArgument, "--stereo",
                  "--stereo draws a second view: it needs --out (and not --no-render)");
    }
    plan.pictures.stereo_baseline = baseline;
  }
  plan.pictures.samples = static_cast<int>(parse_count(options.samples, "--samples", 1, 16));
  plan_optics(options, plan);
  plan.hand_off = pictures::parse_hand_off(options.hand_off, "--hand-off");
  plan.reference_draw = options.reference_draw;
  plan.draw_written = parse_choice<bool>(options.draw, "--draw", "a way to draw",
                                         {{"all", false}, {"written", true}}, "all or written");
  if (plan.draw_written && (!out || !plan.render)) {
    throw Error(ErrorCode::kInvalidArgument, "--draw",
                "--draw written draws the frames written: it needs --out (and not --no-render)");
  }
  for (const auto& [given, option] :
       {std::pair{!options.image_frames.empty(), "--image-frames"},
        std::pair{!options.video.empty(), "--video"}, std::pair{options.annotate, "--annotate"}}) {
    if (!given) continue;
    if (!out) {
      throw Error(ErrorCode::kInvalidArgument, option, std::string(option) + " needs --out");
    }
    if (!plan.render) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  std::string(option) + " draws frames: it cannot go with --no-render");
    }
  }
  PictureFiles& files = plan.files;
  const std::string images = options.image_frames.empty() ? "all" : options.image_frames;
  files.every_image = images == "all";
  if (images != "all" && images != "none") {
    files.image_frames = parse_frames(images, plan.frames, "--image-frames");
  }
  files.videos = parse_videos(options.video.empty() ? "auto" : options.video);
  if (!out || !plan.render) {
    files.every_image = false;
    files.image_frames.clear();
    files.videos.clear();
  }
  files.fps = static_cast<int>(std::lround(plan.fps));
  if (!files.videos.empty() && (files.fps < 1 || files.fps > 240)) {
    throw Error(ErrorCode::kInvalidArgument, "--fps",
                "--fps " + options.fps +
                    ": a video plays at 1 to 240 frames per second "
                    "(--video none writes none)");
  }
  files.annotate = options.annotate;
  for (const auto& [given, option] :
       {std::pair{options.formats != "coco", "--formats"}, std::pair{options.depth, "--depth"},
        std::pair{!options.keypoints.empty(), "--keypoints"}}) {
    if (given && !files.annotate) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  std::string(option) + " is part of the dataset: it needs --annotate");
    }
  }
  // coco.json is always written: it holds the truth the other formats are made from.
  for (const std::string& format : split_list(options.formats)) {
    if (format == "yolo") {
      files.dataset.yolo = true;
    } else if (format == "webdataset") {
      files.dataset.webdataset = true;
    } else if (format != "coco") {
      throw Error(ErrorCode::kInvalidArgument, "--formats",
                  "--formats: '" + format + "' is not a dataset format (coco, yolo, webdataset)");
    }
  }
  files.dataset.depth = options.depth;
  if (!options.keypoints.empty()) {
    files.dataset.keypoints =
        pictures::chosen_keypoints(split_list(options.keypoints), "--keypoints");
  }
  if (!options.length_weights.empty() && !files.annotate) {
    throw Error(ErrorCode::kInvalidArgument, "--length-weight",
                "--length-weight is part of the dataset: it needs --annotate");
  }
  for (const std::string& text : options.length_weights) {
    const std::size_t colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) {
      throw Error(ErrorCode::kInvalidArgument, "--length-weight",
                  "--length-weight '" + text + "': SPECIES:A,B expected");
    }
    const std::vector<double> ab = parse_number_list(text.substr(colon + 1), "--length-weight", 2);
    if (ab[0] <= 0.0 || ab[1] < 2.0 || ab[1] > 4.0) {
      throw Error(ErrorCode::kInvalidArgument, "--length-weight",
                  "--length-weight '" + text + "': a > 0 and 2 <= b <= 4 (W g = a (L cm)^b)");
    }
    files.dataset.weights.push_back({text.substr(0, colon), {ab[0], ab[1]}});
  }
  files.stereo_baseline = plan.pictures.stereo_baseline;
  files.seed = plan.seed;
  for (const auto& [given, option] : {std::pair{!options.distortion.empty(), "--distortion"},
                                      std::pair{!options.noise.empty(), "--noise"}}) {
    if (given && !out) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  std::string(option) + " is the image frames' optics: it needs --out");
    }
  }
  if (!options.distortion.empty()) {
    const std::vector<double> k = parse_number_list(options.distortion, "--distortion", 5);
    files.distortion = {k[0], k[1], k[2], k[3], k[4]};
  }
  if (!options.noise.empty()) {
    const std::vector<double> n = parse_number_list(options.noise, "--noise", 2);
    for (double v : n) {
      if (v < 0.0 || v > 255.0) {
        throw Error(ErrorCode::kInvalidArgument, "--noise",
                    "--noise " + options.noise + ": each sigma is 0 to 255 sRGB levels");
      }
    }
    files.noise = {n[0], n[1]};
  }
  if (files.annotate && !files.every_image && files.image_frames.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--annotate",
                "--annotate annotates the frames written as images: --image-frames is none");
  }
  if (files.annotate && plan.fish > pictures::kMaxAnnotatedFish) {
    throw Error(ErrorCode::kInvalidArgument, "--fish",
                "--fish " + options.fish + " with --annotate: masks hold 16-bit ids, at most " +
                    std::to_string(pictures::kMaxAnnotatedFish) + " fish");
  }
}

}  // namespace

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
  const std::size_t tanks = parse_count(options.tanks, "--tanks", 1, 1024);
  // A hall's tanks hold the default density unless --tank sizes them.
  if (tanks > 1) plan.hall = tank::HallSettings::farm(tanks, plan.fish);
  if (!options.tank.empty()) {
    const auto [diameter, depth] = parse_positive_pair(options.tank, "--tank");
    plan.hall.tank.diameter = diameter;
    plan.hall.tank.depth = depth;
  }
  plan.seed = parse_count(options.seed, "--seed", 0, UINT64_MAX);
  plan.normals = parse_normal_mode(options.normals, "--normals");
  if (!options.mesh_frames.empty() && options.out.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--mesh-frames", "--mesh-frames needs --out");
  }
  plan.mesh_frames = parse_frames(options.mesh_frames, plan.frames, "--mesh-frames");
  if (!options.levels.empty()) {
    tank::SceneLevels levels;
    levels.levels =
        parse_level_options(options.levels, options.triangle_ratio, options.freeze_fins);
    levels.choice.pixel_budget = parse_positive(options.pixel_budget, "--pixel-budget");
    levels.wall_occlusion = options.wall_occlusion;
    if (!plan.mesh_frames.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--mesh-frames",
                  "--mesh-frames writes every fish at full detail: not with --levels");
    }
    if (options.annotate) {
      throw Error(ErrorCode::kInvalidArgument, "--annotate",
                  "--annotate takes its keypoints from every fish at full detail: not with "
                  "--levels");
    }
    if (options.reference_draw) {
      throw Error(ErrorCode::kInvalidArgument, "--reference-draw",
                  "--reference-draw draws every fish at full detail: not with --levels");
    }
    plan.levels = levels;
  }
  plan_pictures(options, plan);
  if (tanks > 1 && plan.pictures.view == pictures::CameraView::kUnderwater) {
    throw Error(ErrorCode::kInvalidArgument, "--camera",
                "--camera underwater is in one tank's water: a hall of --tanks " + options.tanks +
                    " is seen from its own camera above");
  }
  if (!options.out.empty()) check_output_folder(options.out, "--out");
  return plan;
}

}  // namespace finflex::cli

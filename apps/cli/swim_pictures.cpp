#include "swim_pictures.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "camera_file.hpp"
#include "render/png.hpp"

namespace finflex::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string image_name(std::size_t frame) {
  char name[48];
  std::snprintf(name, sizeof name, "frames/frame_%06zu.png", frame);
  return name;
}

}  // namespace

SwimPictureFiles::SwimPictureFiles(const std::string& folder, pictures::TankPictures& pictures,
                                   tank::SwimScene& scene, const PictureFiles& plan,
                                   const nlohmann::ordered_json& info)
    : folder_(folder), pictures_(pictures), plan_(plan) {
  const render::RenderSettings& size = pictures.renderer().settings();
  fs::create_directories(fs::path(folder) / "frames");
  render::VideoOptions options;
  options.width = size.width;
  options.height = size.height;
  options.fps = plan.fps;
  for (const std::string& extension : plan.videos) {
    videos_.push_back(
        render::open_video((fs::path(folder) / ("swim." + extension)).string(), options));
  }
  if (plan.annotate) {
    dataset_ = std::make_unique<pictures::CocoDataset>(folder, scene, pictures.camera(), size.width,
                                                       size.height, info);
  }
  std::ofstream camera(fs::path(folder) / "camera.json");
  camera << pictures::camera_json(pictures.camera(), size.width, size.height).dump(1) << "\n";
  if (!camera) throw Error(ErrorCode::kIo, "--out", "'" + folder + "/camera.json': write failed");
}

PictureFileTimes SwimPictureFiles::add_frame(std::size_t frame, double time_s) {
  PictureFileTimes times;
  const bool image = plan_.image_of(frame);
  if (!image && videos_.empty()) return times;
  Clock::time_point start = Clock::now();
  const render::Image& picture = pictures_.read_image();
  times.read_back = seconds_since(start);
  start = Clock::now();
  if (image) {
    render::write_png((fs::path(folder_) / image_name(frame)).string(), picture);
    ++images_;
  }
  for (const std::unique_ptr<render::VideoWriter>& video : videos_) video->add_frame(picture);
  times.files = seconds_since(start);
  if (image && dataset_) {
    start = Clock::now();
    dataset_->add_frame(frame, time_s, image_name(frame), pictures_.draw_ids());
    times.annotation = seconds_since(start);
  }
  return times;
}

void SwimPictureFiles::finish() {
  for (const std::unique_ptr<render::VideoWriter>& video : videos_) video->finish();
  if (dataset_) dataset_->finish();
}

}  // namespace finflex::cli

#include "swim_pictures.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "camera_file.hpp"
#include "render/png.hpp"
#include "worker_pool.hpp"

namespace finflex::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string image_name(std::size_t frame, std::size_t view) {
  return pictures::frame_file("frames", frame, "png", view);
}

}  // namespace

SwimPictureFiles::SwimPictureFiles(const std::string& folder, pictures::TankPictures& pictures,
                                   tank::SwimScene& scene, const PictureFiles& plan,
                                   const nlohmann::ordered_json& info)
    : folder_(folder),
      pictures_(pictures),
      plan_(plan),
      pool_(std::make_unique<WorkerPool>(WorkerPool::default_workers())) {
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
  // The surface that bends the view rays, where the pictures refract.
  const render::Scene* refraction =
      pictures.look().view_refraction != render::ViewRefraction::kNone ? &pictures.look() : nullptr;
  if (!plan.distortion.none()) {  // one lens for both cameras of a pair: the same intrinsics
    lens_ = std::make_shared<const pictures::LensWarp>(
        plan.distortion, render::pinhole_intrinsics(pictures.camera(), size.width, size.height),
        size.width, size.height, "--distortion");
  }
  if (plan.annotate) {
    pictures::DatasetOptions dataset = plan.dataset;
    dataset.lens = lens_;
    if (refraction) dataset.refraction = *refraction;
    std::vector<render::Camera> cameras;
    for (std::size_t v = 0; v < pictures.views(); ++v) cameras.push_back(pictures.camera(v));
    dataset_ = std::make_unique<pictures::CocoDataset>(folder, scene, cameras, size.width,
                                                       size.height, info, dataset);
  }
  std::ofstream camera(fs::path(folder) / "camera.json");
  const nlohmann::ordered_json camera_file =
      plan.stereo_baseline > 0.0
          ? pictures::stereo_camera_json(pictures.camera(), plan.stereo_baseline, size.width,
                                         size.height, plan.distortion, refraction)
          : pictures::camera_json(pictures.camera(), size.width, size.height, plan.distortion,
                                  refraction);
  camera << camera_file.dump(1) << "\n";
  if (!camera) throw Error(ErrorCode::kIo, "--out", "'" + folder + "/camera.json': write failed");
}

SwimPictureFiles::~SwimPictureFiles() {
  // An error left work in flight: let the pool finish it before the folder goes.
  pool_.reset();
}

PictureFileTimes SwimPictureFiles::add_frame(std::size_t frame, double time_s) {
  PictureFileTimes times;
  const bool image = plan_.image_of(frame);
  if (!plan_.writes(frame)) return times;
  render::Renderer& renderer = pictures_.renderer();
  const std::size_t in_flight = renderer.settings().frames_in_flight;
  // The left (or only) view was drawn by the caller; a stereo pair's right one is drawn
  // here, for the frames written as images (the videos are the left view's).
  const std::size_t views = image ? pictures_.views() : 1;
  for (std::size_t view = 0; view < views; ++view) {
    if (view > 0) pictures_.draw_view(view);
    if (renderer.images_pending() == in_flight) take_frame(&times);  // the oldest first
    renderer.request_image();
    in_flight_.push_back({frame, view});
    if (image && dataset_) {
      const Clock::time_point start = Clock::now();
      if (renderer.ids_pending() == in_flight) take_ids();
      truths_.push_back(dataset_->capture(frame, time_s, image_name(frame, view), view));
      truths_.back().optics = pictures::optics_json(pictures_.optics(), pictures_.look());
      pictures_.request_ids(view);
      collect(false);
      times.annotation += seconds_since(start);
    }
  }
  return times;
}

void SwimPictureFiles::take_frame(PictureFileTimes* times) {
  const auto [frame, view] = in_flight_.front();
  in_flight_.pop_front();
  // An image the pool has handed back, else a new one: no allocation per frame.
  render::Image picture;
  if (!free_images_.empty()) {
    picture = std::move(free_images_.back());
    free_images_.pop_back();
  }
  Clock::time_point start = Clock::now();
  pictures_.renderer().take_image(picture);
  if (times) times->read_back = seconds_since(start);
  start = Clock::now();
  if (view == 0) {
    for (const std::unique_ptr<render::VideoWriter>& video : videos_) video->add_frame(picture);
  }
  if (plan_.image_of(frame)) {
    const std::string path = (fs::path(folder_) / image_name(frame, view)).string();
    // The lens and the sensor on the pool's threads; noise seeded by the frame and view.
    const std::uint64_t seed = (plan_.seed * 1000003u + frame) * 2u + view;
    pngs_.push_back(pool_->submit([this, path, seed, image = std::move(picture)]() mutable {
      if (lens_) {
        render::Image ideal = std::move(image);
        lens_->apply(ideal, image);
      }
      if (!plan_.noise.none()) plan_.noise.apply(image, seed);
      render::write_png(path, image);
      return std::move(image);
    }));
    ++images_;
  } else {
    free_images_.push_back(std::move(picture));
  }
  collect(false);
  if (times) times->files = seconds_since(start);
}

void SwimPictureFiles::take_ids() {
  pictures::CocoDataset::FrameTruth truth = std::move(truths_.front());
  truths_.pop_front();
  pictures_.renderer().take_ids(truth.ids);
  const pictures::CocoDataset* dataset = dataset_.get();
  annotations_.push_back(
      pool_->submit([dataset, truth = std::move(truth)] { return dataset->annotate(truth); }));
}

namespace {

// Takes the finished results at the front of `waiting` (all of them while more than
// `keep` wait), in order, into `take`; rethrows a task's error.
template <typename Result, typename Take>
void take_finished(std::deque<std::future<Result>>& waiting, std::size_t keep, Take take) {
  while (!waiting.empty() &&
         (waiting.size() > keep ||
          waiting.front().wait_for(std::chrono::seconds(0)) == std::future_status::ready)) {
    take(waiting.front().get());
    waiting.pop_front();
  }
}

}  // namespace

void SwimPictureFiles::collect(bool all) {
  const std::size_t keep = all ? 0 : pool_->size();
  take_finished(pngs_, keep,
                [this](render::Image image) { free_images_.push_back(std::move(image)); });
  take_finished(annotations_, keep, [this](pictures::CocoDataset::FrameAnnotations frame) {
    dataset_->append(std::move(frame));
  });
}

void SwimPictureFiles::finish() {
  while (!in_flight_.empty()) take_frame(nullptr);
  while (!truths_.empty()) take_ids();
  collect(true);
  for (const std::unique_ptr<render::VideoWriter>& video : videos_) video->finish();
  if (dataset_) dataset_->finish();
}

}  // namespace finflex::cli

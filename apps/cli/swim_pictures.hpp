// What `finflex swim --out DIR` writes of the rendered frames: PNG frames
// (frames/frame_NNNNNN.png), videos of every frame (swim.mp4 / swim.gif through
// ffmpeg, swim.png an APNG), camera.json, and with --annotate the dataset
// (masks/, coco.json: pictures/coco_dataset.hpp); with a stereo pair, each image frame's
// right view beside it (frame_NNNNNN_right.png, its mask and labels alike). Everything
// goes into the run's staging folder (staging_folder.hpp).
//
// Nothing here waits for the frame just drawn: its colour image is read back
// asynchronously (Renderer::request_image; the renderer's frames in flight) and taken
// a few frames later; PNG encoding, masks and annotations run on a pool of threads
// (worker_pool.hpp); the videos get their frames and coco.json its annotations in
// frame order, so the files are the same as one thread would write.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "coco_dataset.hpp"
#include "lens.hpp"
#include "render/video.hpp"
#include "tank_pictures.hpp"

namespace finflex::cli {

struct PictureFiles {
  bool every_image = true;             // a PNG of every frame
  std::set<std::size_t> image_frames;  // else these frames
  std::vector<std::string> videos;     // extensions: "mp4", "gif", "png" (APNG)
  bool annotate = false;               // masks and COCO for every frame written as an image
  pictures::DatasetOptions dataset;    // with annotate: YOLO, depth
  double stereo_baseline = 0.0;        // > 0: a stereo pair's right view too (metres)
  // The image frames' lens and sensor (pictures/lens.hpp; the videos stay ideal); noise
  // seeded by `seed`, the frame and the view.
  pictures::LensDistortion distortion;
  pictures::SensorNoise noise;
  std::uint64_t seed = 0;
  int fps = 30;  // the videos'

  bool image_of(std::size_t frame) const { return every_image || image_frames.count(frame) > 0; }
  // Whether frame `frame` writes anything (an image or a video frame): the others are
  // simulated and deformed but not drawn.
  bool writes(std::size_t frame) const { return !videos.empty() || image_of(frame); }
};

// Seconds of the frame loop's thread that one frame's files took (the pool's work
// runs beside it).
struct PictureFileTimes {
  double read_back = 0.0;   // taking colour images from the renderer (their fences)
  double files = 0.0;       // handing PNGs to the pool, video frames to the encoders
  double annotation = 0.0;  // the id pass, keypoints, appending to coco.json
};

class SwimPictureFiles {
 public:
  // Opens the videos and the dataset in `folder` and writes camera.json.
  SwimPictureFiles(const std::string& folder, pictures::TankPictures& pictures,
                   tank::SwimScene& scene, const PictureFiles& plan,
                   const nlohmann::ordered_json& info);

  ~SwimPictureFiles();
  // Frame `frame` at time_s, after pictures.draw() of it (only for frames the plan
  // writes): its image, video frame and annotations as the plan says (written once the
  // frame is taken, a few frames on).
  PictureFileTimes add_frame(std::size_t frame, double time_s);
  // Writes what is still in flight, completes the videos and coco.json.
  void finish();

  std::size_t images_written() const { return images_; }
  std::size_t annotations() const { return dataset_ ? dataset_->annotation_count() : 0; }

 private:
  std::string folder_;
  pictures::TankPictures& pictures_;
  PictureFiles plan_;
  std::vector<std::unique_ptr<render::VideoWriter>> videos_;
  std::unique_ptr<pictures::CocoDataset> dataset_;
  std::shared_ptr<const pictures::LensWarp> lens_;  // with a distortion; the dataset's too
  std::size_t images_ = 0;

  // Takes the oldest frame in flight: its video frame, its PNG to the pool (the
  // loop's seconds of it into `times`, when given).
  void take_frame(PictureFileTimes* times);
  // Takes the oldest id pass in flight into its frame's truth and hands the frame's
  // annotation to the pool.
  void take_ids();
  // Waits for finished pool work in order (all of it: `all`; else while more than the
  // pool's size is waiting), rethrowing its errors, appending annotations.
  void collect(bool all);
  std::unique_ptr<class WorkerPool> pool_;
  struct View {
    std::size_t frame = 0;
    std::size_t view = 0;
  };
  std::deque<View> in_flight_;                   // images requested from the renderer
  std::deque<std::future<render::Image>> pngs_;  // each hands its image back
  std::vector<render::Image> free_images_;
  std::deque<pictures::CocoDataset::FrameTruth> truths_;  // their id passes in flight
  std::deque<std::future<pictures::CocoDataset::FrameAnnotations>> annotations_;
};

}  // namespace finflex::cli

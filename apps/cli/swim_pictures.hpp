// What `finflex swim --out DIR` writes of the rendered frames: PNG frames
// (frames/frame_NNNNNN.png), videos of every frame (swim.mp4 / swim.gif through
// ffmpeg, swim.png an APNG), camera.json, and with --annotate the dataset
// (masks/, coco.json: pictures/coco_dataset.hpp). Everything goes into the run's
// staging folder (staging_folder.hpp).
#pragma once

#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "coco_dataset.hpp"
#include "render/video.hpp"
#include "tank_pictures.hpp"

namespace finflex::cli {

struct PictureFiles {
  bool every_image = true;             // a PNG of every frame
  std::set<std::size_t> image_frames;  // else these frames
  std::vector<std::string> videos;     // extensions: "mp4", "gif", "png" (APNG)
  bool annotate = false;               // masks and COCO for every frame written as an image
  int fps = 30;                        // the videos'

  bool image_of(std::size_t frame) const { return every_image || image_frames.count(frame) > 0; }
};

// Seconds one frame's files took.
struct PictureFileTimes {
  double read_back = 0.0;   // the colour image from the renderer
  double files = 0.0;       // PNG encoding and writing, video encoding
  double annotation = 0.0;  // the id pass, masks, keypoints, COCO
};

class SwimPictureFiles {
 public:
  // Opens the videos and the dataset in `folder` and writes camera.json.
  SwimPictureFiles(const std::string& folder, pictures::TankPictures& pictures,
                   tank::SwimScene& scene, const PictureFiles& plan,
                   const nlohmann::ordered_json& info);

  // Frame `frame` at time_s, after pictures.draw() of it: its image, video frame and
  // annotations as the plan says.
  PictureFileTimes add_frame(std::size_t frame, double time_s);
  // Completes the videos and coco.json.
  void finish();

  std::size_t images_written() const { return images_; }
  std::size_t annotations() const { return dataset_ ? dataset_->annotation_count() : 0; }

 private:
  std::string folder_;
  pictures::TankPictures& pictures_;
  PictureFiles plan_;
  std::vector<std::unique_ptr<render::VideoWriter>> videos_;
  std::unique_ptr<pictures::CocoDataset> dataset_;
  std::size_t images_ = 0;
};

}  // namespace finflex::cli

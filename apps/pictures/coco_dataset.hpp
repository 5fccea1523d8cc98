// The machine-vision dataset of a swim (`finflex swim --annotate`): for every frame
// written as an image, an instance mask and COCO annotations whose ground truth is the
// engine's own deformed geometry:
//
//   masks/frame_NNNNNN.png   16-bit grey: 1 + the fish's index in the tank where that
//                            fish is the nearest surface at the pixel's centre, 0 else
//   coco.json                COCO "instances" with keypoints: one category per species
//                            (keypoints "snout", "tail_fork"), one image per frame
//                            (per camera of a stereo pair),
//                            one annotation per fish with at least one pixel
//
// Each annotation: "bbox" [x, y, w, h] (the mask's tight box, pixel edges), "area" (its
// pixels: the visible area), "segmentation" (the mask as COCO's compressed run-length
// counts), "iscrowd" 0, "keypoints" [u, v, visibility] x 6 (the projected vertices,
// visibility 2 where nothing nearer covers the pixel, 1 where something does, 0 with
// u = v = 0 outside the image), "num_keypoints", and the truth beyond COCO's fields:
// "fish_id" (the tank's index: the same fish in every frame, for tracking),
// "species", "length_m" (total length, snout to tail tip), "fork_length_m",
// "keypoints_camera_m" (the points in camera coordinates, OpenCV axes, metres; null for
// a part the species lacks), "spine_camera_m" (kSpinePoints points of the midline from
// the snout to the tail fork, camera coordinates) and "spine_length_m" (its length).
// "weight_kg" (the length-weight relation W = a L^b, L the total length in cm, W in g:
// the category's "length_weight").
// coco.json is streamed: memory does not grow with the frames.
//
// With DatasetOptions: `yolo` also writes Ultralytics YOLO's three datasets of the same
// frames (yolo/detect, yolo/segment, yolo/pose: images/ as hard links to the frames,
// labels/, dataset.yaml; yolo_labels.hpp), `depth` each frame's depth in metres
// (depth/frame_NNNNNN.npy: float32, height x width, row-major from the top, the camera
// axis' distance of the nearest surface at each pixel's centre, 0 where nothing is).
#pragma once

#include <array>
#include <cstddef>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "fish_keypoints.hpp"
#include "landmarks.hpp"
#include "lens.hpp"
#include "render/camera.hpp"
#include "render/id_image.hpp"
#include "render/scene.hpp"
#include "swim_scene.hpp"

namespace finflex::pictures {

// Ids are 16-bit in the masks: at most this many fish.
constexpr std::size_t kMaxAnnotatedFish = 65535;

// A frame's file in `folder`: "folder/frame_NNNNNN.extension", the right view of a
// stereo pair "folder/frame_NNNNNN_right.extension".
std::string frame_file(const char* folder, std::size_t frame, const char* extension,
                       std::size_t view = 0);

// W = a L^b: W in grams, L the total length in centimetres (FishBase's units).
struct LengthWeight {
  double a = 0.01;
  double b = 3.0;
  double grams(double length_m) const;
};

struct DatasetOptions {
  bool yolo = false;   // Ultralytics YOLO detect, segment and pose datasets too
  bool depth = false;  // depth/frame_NNNNNN.npy per frame
  // WebDataset tar shards of the same samples (webdataset/shard-NNNNNN.tar, 1,000 a
  // shard): per image KEY.png, KEY.mask.png, KEY.depth.npy (with depth), KEY.json
  // (its coco.json image and annotations).
  bool webdataset = false;
  // The pictures' lens (lens.hpp; null: none), for the frame's size and camera:
  // masks, depth and keypoints go through it too.
  std::shared_ptr<const LensWarp> lens;
  // The scene whose surface or camera port bends the view rays (render::Scene::view_refraction,
  // as the pictures were drawn): keypoints where the camera sees them through it.
  std::optional<render::Scene> refraction;
  // The keypoints annotated, indices into kKeypointNames in its order (chosen_keypoints):
  // by default all. Each must be a part of some species' rig (kInvalidArgument naming
  // "--keypoints" otherwise).
  std::vector<std::size_t> keypoints{0, 1, 2, 3, 4, 5};
  // Length-weight relations by species name; the others take LengthWeight{}.
  std::vector<std::pair<std::string, LengthWeight>> weights;
};

class CocoDataset {
 public:
  // Opens `folder`/coco.json and makes `folder`/masks. kInvalidArgument naming "fish"
  // when the tank has more than kMaxAnnotatedFish fish; kIo when a file cannot be made.
  // `cameras`: one, or a stereo pair's two (left, right; TankPictures::camera(view)):
  // each frame then has an image per camera (ids 2 frame + 1 and 2 frame + 2, each
  // naming the other as "stereo_pair_id").
  CocoDataset(const std::string& folder, tank::SwimScene& scene,
              const std::vector<render::Camera>& cameras, int width, int height,
              const nlohmann::ordered_json& info, const DatasetOptions& options = {});

  // A frame in three steps, so that the work in the middle can run on another thread
  // while the next frames are drawn: frame `frame` (time_s into the swim), whose
  // colour image is `image_file` (relative to the folder); first what must be taken
  // while the scene's batches hold that frame (the keypoints are read from them; the
  // scene's thread), to which the caller adds the frame's id pass (`ids`, once read back),
  struct FrameTruth {
    std::size_t frame = 0;
    std::size_t view = 0;  // the camera
    double time_s = 0.0;
    std::string image_file;
    render::IdImage ids;
    // Per species, per vertex read (its keypoints' and its spine's), per instance: the
    // deformed vertex. The views of one frame share them.
    std::shared_ptr<const std::vector<std::vector<std::vector<glm::vec3>>>> vertices;
    // The image's water and light (frame_optics.hpp optics_json), or null.
    nlohmann::ordered_json optics;
  };
  FrameTruth capture(std::size_t frame, double time_s, const std::string& image_file,
                     std::size_t view = 0);
  // the mask file and the frame's annotations (any thread; several frames at once;
  // kInvalidArgument naming "ids" unless they are the dataset's width x height),
  struct FrameAnnotations {
    // Each annotation as coco.json's text (dumped on the annotating thread), starting
    // {"id":0, where append gives it its id.
    std::vector<std::string> annotations;
    nlohmann::ordered_json image;
  };
  FrameAnnotations annotate(const FrameTruth& truth) const;
  // and coco.json's part of it, frames in order (the thread that made the dataset).
  void append(FrameAnnotations frame);
  // Writes the images' list and closes coco.json; with YOLO, links each frame's image
  // into the YOLO datasets (once its PNG is written) and writes their YAMLs. kIo when
  // a file could not be written.
  void finish();

  std::size_t annotation_count() const { return next_annotation_ - 1; }

 private:
  struct SpeciesTruth {
    FishLandmarks landmarks;
    std::vector<std::uint32_t> slots;  // the slots read each frame, each once
    std::array<std::optional<std::size_t>, kKeypointCount> keypoints;  // index into slots
    std::array<std::array<std::size_t, 2>, kSpinePoints> spine{};      // index into slots
    std::shared_ptr<SlotPositionReader> reader;                        // made on the first capture
  };

  std::string folder_;
  tank::SwimScene& scene_;
  std::vector<render::Camera> cameras_;
  int width_;
  int height_;
  std::vector<glm::dmat4> camera_from_world_;  // per camera
  std::vector<SpeciesTruth> species_;
  // The last capture's frame and vertices: a stereo pair's second view reads nothing.
  std::size_t captured_frame_ = 0;
  std::shared_ptr<const std::vector<std::vector<std::vector<glm::vec3>>>> captured_;
  std::vector<std::size_t> instance_of_fish_;  // per tank fish, its index in its species
  struct FishTruth {
    std::size_t species = 0;
    double length = 0.0;
  };
  std::vector<FishTruth> fish_;        // per tank fish: what does not change in a swim
  std::vector<std::string> names_;     // per species
  std::vector<LengthWeight> weights_;  // per species
  DatasetOptions options_;
  void write_shards() const;  // webdataset/: the images written, their samples
  std::ofstream coco_;
  nlohmann::ordered_json images_ = nlohmann::ordered_json::array();
  std::size_t next_annotation_ = 1;
};

}  // namespace finflex::pictures

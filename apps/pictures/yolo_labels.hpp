// Ultralytics YOLO's label layout (docs.ultralytics.com/datasets/detect, .../segment,
// .../pose): one text file per image, one line per object, its coordinates divided by
// the image's width (x) and height (y), so in 0..1:
//
//   detect:   class x_centre y_centre width height
//   segment:  class x1 y1 x2 y2 ...             (the object's outline, >= 3 points)
//   pose:     class x_centre y_centre width height x1 y1 v1 ... xK yK vK
//
// `class` is the category's index from 0; a pose's keypoints are COCO's (v 0: outside
// the image, written 0 0 0; 1: hidden; 2: seen), their count the dataset YAML's
// kpt_shape [K, 3]. Boxes are the mask's tight box in pixel edges (COCO's bbox).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "instance_masks.hpp"
#include "render/id_image.hpp"

namespace finflex::pictures {

enum class YoloTask { kDetect, kSegment, kPose };
const char* to_string(YoloTask task);  // "detect", "segment", "pose"
constexpr std::array<YoloTask, 3> kYoloTasks{YoloTask::kDetect, YoloTask::kSegment,
                                             YoloTask::kPose};

// The outline of `mask`'s pixels in `ids` (pixel-edge coordinates, corners only):
// each 4-connected part's outer boundary, clockwise on the image; several parts are
// joined into one polygon by going to each next part's nearest point and back (as
// Ultralytics' own COCO converter joins a mask's polygons). Holes are not cut out:
// the outline's area is the mask's area plus any hole's (a fish wholly inside another's
// silhouette). Work: the box's pixels, and per joined part its points times the
// polygon's.
std::vector<glm::dvec2> mask_outline(const render::IdImage& ids, const InstanceMask& mask);

// One label line (no newline) of `task` for an object of class `category` with `mask`
// (its box), `outline` (segment) and `keypoints` (pose: u, v, visibility each) in an
// image of width x height pixels.
std::string yolo_line(YoloTask task, std::size_t category, const InstanceMask& mask,
                      const std::vector<glm::dvec2>& outline,
                      const std::vector<std::array<double, 3>>& keypoints, int width, int height);

// The dataset YAML Ultralytics reads beside images/ and labels/ (no `path`: the YAML's
// folder), train and val both the images; `names` in class order; pose datasets get
// kpt_shape [keypoints, 3] and flip_idx (`flip`: each keypoint's mirror image).
std::string yolo_dataset_yaml(YoloTask task, const std::vector<std::string>& names,
                              const std::vector<std::string>& keypoint_names,
                              const std::vector<std::size_t>& flip);

}  // namespace finflex::pictures

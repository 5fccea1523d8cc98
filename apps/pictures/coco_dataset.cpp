#include "coco_dataset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "fish_keypoints.hpp"
#include "instance_masks.hpp"
#include "render/png16.hpp"
#include "render/refraction.hpp"
#include "tar_shards.hpp"
#include "yolo_labels.hpp"

namespace finflex::pictures {

namespace {

// A keypoint counts as hidden when the surface seen at its pixel is this much nearer
// (metres) and belongs to something else.
constexpr double kOcclusionTolerance = 0.005;

// The chosen keypoints (indices into kKeypointNames): their names; keypoint k's place
// among them (chosen.size() when not chosen); the skeleton's edges between them
// (snout-fork, fork-caudal tips, snout-pectoral tips; 1-based, COCO's); and YOLO's
// flip_idx, each one's mirror image's place.
std::vector<std::string> chosen_names(const std::vector<std::size_t>& chosen) {
  std::vector<std::string> out;
  for (std::size_t k : chosen) out.emplace_back(kKeypointNames[k]);
  return out;
}

std::size_t place_of(const std::vector<std::size_t>& chosen, std::size_t k) {
  return std::size_t(std::find(chosen.begin(), chosen.end(), k) - chosen.begin());
}

nlohmann::ordered_json skeleton(const std::vector<std::size_t>& chosen) {
  constexpr std::size_t kEdges[][2] = {{0, 1}, {1, 2}, {1, 3}, {0, 4}, {0, 5}};
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& edge : kEdges) {
    const std::size_t a = place_of(chosen, edge[0]), b = place_of(chosen, edge[1]);
    if (a < chosen.size() && b < chosen.size()) out.push_back({a + 1, b + 1});
  }
  return out;
}

std::vector<std::size_t> flip_places(const std::vector<std::size_t>& chosen) {
  std::vector<std::size_t> out;
  for (std::size_t k : chosen) out.push_back(place_of(chosen, kKeypointFlip[k]));
  return out;
}

nlohmann::ordered_json categories(const tank::SwimScene& scene,
                                  const std::vector<LengthWeight>& weights,
                                  const std::vector<std::size_t>& chosen) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t s = 0; s < scene.species().size(); ++s) {
    out.push_back({{"id", s + 1},
                   {"name", scene.species()[s].name},
                   {"supercategory", "fish"},
                   {"keypoints", chosen_names(chosen)},
                   {"skeleton", skeleton(chosen)},
                   {"length_weight",
                    {{"a", weights[s].a}, {"b", weights[s].b}, {"units", "W g = a (L cm)^b"}}}});
  }
  return out;
}

// numpy's .npy (format 1.0): magic, a header dict padded to 64 bytes, the data.
void write_depth_npy(const std::string& path, const render::IdImage& ids) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(ids.height) + ", " + std::to_string(ids.width) + "), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const auto length = static_cast<std::uint16_t>(header.size());
  const char little[2] = {char(length & 0xff), char(length >> 8)};
  out.write(little, 2);
  out << header;
  std::vector<float> depth(ids.depth.size());
  for (std::size_t k = 0; k < depth.size(); ++k) {
    depth[k] = std::isfinite(ids.depth[k]) ? ids.depth[k] : 0.0f;  // nothing drawn: 0
  }
  out.write(reinterpret_cast<const char*>(depth.data()), std::streamsize(depth.size() * 4));
  if (!out) throw Error(ErrorCode::kIo, "--out", "'" + path + "': write failed");
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw Error(ErrorCode::kIo, "--out", "'" + path + "': write failed");
}

void require_written(const std::ofstream& stream, const std::string& path) {
  if (!stream) throw Error(ErrorCode::kIo, "--out", "'" + path + "': write failed");
}

}  // namespace

std::string frame_file(const char* folder, std::size_t frame, const char* extension,
                       std::size_t view) {
  char name[96];
  std::snprintf(name, sizeof name, "%s/frame_%06zu%s.%s", folder, frame, view ? "_right" : "",
                extension);
  return name;
}

double LengthWeight::grams(double length_m) const { return a * std::pow(100.0 * length_m, b); }

CocoDataset::CocoDataset(const std::string& folder, tank::SwimScene& scene,
                         const std::vector<render::Camera>& cameras, int width, int height,
                         const nlohmann::ordered_json& info, const DatasetOptions& options)
    : folder_(folder),
      scene_(scene),
      cameras_(cameras),
      width_(width),
      height_(height),
      options_(options) {
  for (const render::Camera& camera : cameras_)
    camera_from_world_.push_back(render::camera_from_world(camera));
  const std::vector<tank::Fish>& fish = scene.hall().fish();
  if (fish.size() > kMaxAnnotatedFish) {
    throw Error(ErrorCode::kInvalidArgument, "fish",
                "--annotate: " + std::to_string(fish.size()) +
                    " fish, but masks hold 16-bit ids: at most " +
                    std::to_string(kMaxAnnotatedFish));
  }
  for (const tank::Species& species : scene.species()) {
    SpeciesTruth truth;
    truth.landmarks = find_landmarks(species.swim.model());
    if (species.deformer) {
      const std::vector<std::uint32_t>& slot_of = species.deformer->slot_of_vertex();
      const auto read = [&](std::uint32_t vertex) {
        const std::uint32_t slot = slot_of[vertex];
        const auto found = std::find(truth.slots.begin(), truth.slots.end(), slot);
        if (found != truth.slots.end()) return std::size_t(found - truth.slots.begin());
        truth.slots.push_back(slot);
        return truth.slots.size() - 1;
      };
      for (std::size_t k = 0; k < kKeypointCount; ++k) {
        if (truth.landmarks.keypoints[k]) truth.keypoints[k] = read(*truth.landmarks.keypoints[k]);
      }
      for (std::size_t p = 0; p < kSpinePoints; ++p) {
        truth.spine[p] = {read(truth.landmarks.spine[p][0]), read(truth.landmarks.spine[p][1])};
      }
    }
    species_.push_back(truth);
  }
  for (std::size_t k : options_.keypoints) {
    const bool somewhere =
        std::any_of(species_.begin(), species_.end(),
                    [&](const SpeciesTruth& t) { return t.landmarks.keypoints.at(k).has_value(); });
    if (!somewhere) {
      throw Error(ErrorCode::kInvalidArgument, "--keypoints",
                  std::string("--keypoints: no species' rig has ") + kKeypointNames[k] +
                      " (it comes from a part named " + kKeypointParts[k] + ")");
    }
  }
  std::vector<std::size_t> per_species(scene.species().size(), 0);
  for (const tank::Fish& f : fish) {
    instance_of_fish_.push_back(per_species[f.species]++);
    fish_.push_back({f.species, f.length});
  }
  for (const tank::Species& species : scene.species()) names_.push_back(species.name);
  // By default FishBase's yardstick of a fusiform fish (10 g at 10 cm) with isometric
  // growth (docs/dataset.md "Weights"); the options' relations by species name.
  weights_.assign(names_.size(), LengthWeight{});
  for (const auto& [name, relation] : options_.weights) {
    const auto found = std::find(names_.begin(), names_.end(), name);
    if (found == names_.end()) {
      throw Error(ErrorCode::kInvalidArgument, "--length-weight",
                  "--length-weight: no species '" + name + "' in the tank");
    }
    weights_[std::size_t(found - names_.begin())] = relation;
  }

  const std::filesystem::path root(folder);
  std::filesystem::create_directories(root / "masks");
  if (options_.depth) std::filesystem::create_directories(root / "depth");
  if (options_.webdataset) std::filesystem::create_directories(root / "webdataset" / "samples");
  if (options_.yolo) {
    for (YoloTask task : kYoloTasks) {
      std::filesystem::create_directories(root / "yolo" / to_string(task) / "images");
      std::filesystem::create_directories(root / "yolo" / to_string(task) / "labels");
    }
  }
  const std::string path = (std::filesystem::path(folder) / "coco.json").string();
  coco_.open(path, std::ios::binary);
  nlohmann::ordered_json head;
  head["info"] = info;
  head["licenses"] = nlohmann::ordered_json::array();
  head["categories"] = categories(scene, weights_, options_.keypoints);
  const std::string text = head.dump();
  coco_ << text.substr(0, text.size() - 1) << ",\"annotations\":[";  // the object stays open
  require_written(coco_, path);
}

CocoDataset::FrameTruth CocoDataset::capture(std::size_t frame, double time_s,
                                             const std::string& image_file, std::size_t view) {
  FrameTruth truth;
  truth.frame = frame;
  truth.view = view;
  truth.time_s = time_s;
  truth.image_file = image_file;
  // Keypoints and spines of every fish, from the engine's deformed vertices: read once
  // a frame, whatever its views.
  if (!captured_ || captured_frame_ != frame) {
    auto vertices =
        std::make_shared<std::vector<std::vector<std::vector<glm::vec3>>>>(scene_.species().size());
    for (std::size_t s = 0; s < scene_.species().size(); ++s) {
      tank::Species& species = scene_.species()[s];
      if (!species.deformer) continue;
      SpeciesTruth& truth_of = species_[s];
      const DeviceBatch& batch = species.batch();
      if (!truth_of.reader) {
        truth_of.reader = std::make_shared<SlotPositionReader>(
            species.deformer->context(), truth_of.slots, batch.shape.instance_count,
            batch.shape.plane_stride);
      }
      const tank::BatchReading reading(species);
      (*vertices)[s] = truth_of.reader->read(species.deformer->context().queue(), batch);
    }
    captured_ = std::move(vertices);
    captured_frame_ = frame;
  }
  truth.vertices = captured_;
  return truth;
}

CocoDataset::FrameAnnotations CocoDataset::annotate(const FrameTruth& truth) const {
  render::IdImage distorted;
  const LensWarp* lens = options_.lens.get();
  if (lens) lens->apply(truth.ids, distorted);  // the truth through the pictures' lens
  const render::IdImage& ids = lens ? distorted : truth.ids;
  const auto pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  if (ids.width != width_ || ids.height != height_ || ids.ids.size() != pixels) {
    throw Error(ErrorCode::kInvalidArgument, "ids",
                "ids: an id pass of " + std::to_string(ids.width) + "x" +
                    std::to_string(ids.height) + " (" + std::to_string(ids.ids.size()) +
                    " ids) for a " + std::to_string(width_) + "x" + std::to_string(height_) +
                    " dataset");
  }
  const std::size_t views = cameras_.size();
  const std::size_t image_id = views * truth.frame + truth.view + 1;
  const render::Camera& camera = cameras_.at(truth.view);
  const glm::dmat4& camera_from_world = camera_from_world_.at(truth.view);
  // The mask file: ids as they are (<= 65535).
  render::Image16 mask;
  mask.width = ids.width;
  mask.height = ids.height;
  mask.samples.assign(ids.ids.begin(), ids.ids.end());
  render::write_png16(
      (std::filesystem::path(folder_) / frame_file("masks", truth.frame, "png", truth.view))
          .string(),
      mask);

  if (options_.depth) {
    write_depth_npy(
        (std::filesystem::path(folder_) / frame_file("depth", truth.frame, "npy", truth.view))
            .string(),
        ids);
  }
  FrameAnnotations out;
  std::array<std::string, kYoloTasks.size()> labels;
  const std::vector<InstanceMask> masks = instance_masks(ids);
  const render::PinholeIntrinsics k = render::pinhole_intrinsics(camera, width_, height_);
  for (const InstanceMask& m : masks) {
    const std::size_t f = m.id - 1;
    const FishTruth& one = fish_[f];
    const std::size_t instance = instance_of_fish_[f];
    nlohmann::ordered_json keypoints = nlohmann::ordered_json::array();
    nlohmann::ordered_json camera_points = nlohmann::ordered_json::array();
    std::vector<std::array<double, 3>> yolo_keypoints;
    int labelled = 0;
    const SpeciesTruth& species = species_[one.species];
    const std::vector<std::vector<glm::vec3>>& vertices = (*truth.vertices)[one.species];
    const auto in_camera = [&](std::size_t read) {
      const glm::dvec3 world(vertices[read][instance]);
      return glm::dvec3(camera_from_world * glm::dvec4(world, 1.0));
    };
    for (std::size_t chosen : options_.keypoints) {
      const std::optional<std::size_t>& read = species.keypoints[chosen];
      if (!read) {  // a part this species lacks
        keypoints.insert(keypoints.end(), {0.0, 0.0, 0});
        yolo_keypoints.push_back({0.0, 0.0, 0.0});
        camera_points.push_back(nullptr);
        continue;
      }
      const glm::dvec3 p = in_camera(*read);
      camera_points.push_back({p.x, p.y, p.z});
      // Seen through the water surface, the keypoint's pixel is its apparent point's
      // (at the same depth).
      const glm::dvec3 seen =
          options_.refraction
              ? glm::dvec3(camera_from_world *
                           glm::dvec4(render::apparent_point(*options_.refraction, camera,
                                                             glm::dvec3(vertices[*read][instance])),
                                      1.0))
              : p;
      glm::dvec2 uv{k.fx * seen.x / seen.z + k.cx, k.fy * seen.y / seen.z + k.cy};
      if (lens) uv = lens->distort_pixel(uv);
      const double u = uv.x, v = uv.y;
      const bool inside = p.z > double(camera.near_plane) && u >= 0.0 && v >= 0.0 &&
                          u < double(width_) && v < double(height_);
      if (!inside) {
        keypoints.insert(keypoints.end(), {0.0, 0.0, 0});
        yolo_keypoints.push_back({0.0, 0.0, 0.0});
        continue;
      }
      const std::size_t pixel = ids.index(static_cast<int>(u), static_cast<int>(v));
      const bool hidden =
          ids.ids[pixel] != m.id && double(ids.depth[pixel]) < p.z - kOcclusionTolerance;
      keypoints.insert(keypoints.end(), {u, v, hidden ? 1 : 2});
      yolo_keypoints.push_back({u, v, hidden ? 1.0 : 2.0});
      ++labelled;
    }
    if (options_.yolo) {
      const std::vector<glm::dvec2> outline = mask_outline(ids, m);
      for (std::size_t t = 0; t < kYoloTasks.size(); ++t) {
        labels[t] +=
            yolo_line(kYoloTasks[t], one.species, m, outline, yolo_keypoints, width_, height_) +
            "\n";
      }
    }
    nlohmann::ordered_json annotation;
    annotation["id"] = 0;  // append numbers them
    annotation["image_id"] = image_id;
    annotation["category_id"] = one.species + 1;
    annotation["bbox"] = {m.x_min, m.y_min, m.x_max - m.x_min + 1, m.y_max - m.y_min + 1};
    annotation["area"] = m.area;
    annotation["segmentation"] = {{"size", {ids.height, ids.width}},
                                  {"counts", compress_counts(m.counts)}};
    annotation["iscrowd"] = 0;
    annotation["keypoints"] = keypoints;
    annotation["num_keypoints"] = labelled;
    annotation["fish_id"] = f;
    annotation["species"] = names_[one.species];
    annotation["length_m"] = one.length;
    annotation["fork_length_m"] = one.length * species_[one.species].landmarks.fork_fraction;
    annotation["weight_kg"] = 1e-3 * weights_[one.species].grams(one.length);
    annotation["keypoints_camera_m"] = camera_points;
    nlohmann::ordered_json spine = nlohmann::ordered_json::array();
    double spine_length = 0.0;
    glm::dvec3 last(0.0);
    for (std::size_t point = 0; point < kSpinePoints; ++point) {
      const std::array<std::size_t, 2>& ends = species.spine[point];
      const glm::dvec3 p = 0.5 * (in_camera(ends[0]) + in_camera(ends[1]));
      if (point > 0) spine_length += glm::length(p - last);
      last = p;
      spine.push_back({p.x, p.y, p.z});
    }
    annotation["spine_camera_m"] = spine;
    annotation["spine_length_m"] = spine_length;
    out.annotations.push_back(annotation.dump());
  }
  if (options_.yolo) {  // every image gets its label file, empty when no fish is seen
    for (std::size_t t = 0; t < kYoloTasks.size(); ++t) {
      const std::filesystem::path folder =
          std::filesystem::path(folder_) / "yolo" / to_string(kYoloTasks[t]);
      write_text((folder / frame_file("labels", truth.frame, "txt", truth.view)).string(),
                 labels[t]);
    }
  }
  out.image = {{"id", image_id},
               {"file_name", truth.image_file},
               {"mask_file", frame_file("masks", truth.frame, "png", truth.view)},
               {"width", ids.width},
               {"height", ids.height},
               {"frame", truth.frame},
               {"time_s", truth.time_s},
               {"fish_in_tank", fish_.size()},
               {"fish_visible", masks.size()}};
  if (options_.depth) out.image["depth_file"] = frame_file("depth", truth.frame, "npy", truth.view);
  if (views == 2) {
    out.image["camera"] = truth.view == 0 ? "left" : "right";
    out.image["stereo_pair_id"] = truth.view == 0 ? image_id + 1 : image_id - 1;
  }
  if (!truth.optics.is_null()) out.image["optics"] = truth.optics;
  return out;
}

namespace {

std::string sample_key(const nlohmann::ordered_json& image) {
  return std::filesystem::path(image["file_name"].get<std::string>()).stem().string();
}

}  // namespace

void CocoDataset::append(FrameAnnotations frame) {
  constexpr std::string_view kUnnumbered = "{\"id\":0";
  for (std::string& annotation : frame.annotations) {
    if (annotation.compare(0, kUnnumbered.size(), kUnnumbered) != 0) {
      throw Error(ErrorCode::kInvalidArgument, "annotations",
                  "annotations: an annotation not made by annotate");
    }
    annotation.replace(0, kUnnumbered.size(), "{\"id\":" + std::to_string(next_annotation_++));
    coco_ << (annotation_count() == 1 ? "\n" : ",\n") << annotation;
  }
  if (options_.webdataset) {  // the sample's JSON until the shards are packed
    // As nlohmann's dump of {"image": ..., "annotations": [...]} writes it.
    std::string sample = "{\"image\":" + frame.image.dump() + ",\"annotations\":[";
    for (std::size_t k = 0; k < frame.annotations.size(); ++k) {
      if (k > 0) sample += ',';
      sample += frame.annotations[k];
    }
    sample += "]}";
    write_text((std::filesystem::path(folder_) / "webdataset" / "samples" /
                (sample_key(frame.image) + ".json"))
                   .string(),
               sample);
  }
  images_.push_back(std::move(frame.image));
  require_written(coco_, folder_ + "/coco.json");
}

void CocoDataset::finish() {
  coco_ << "\n],\"images\":" << images_.dump() << "}\n";
  coco_.close();
  require_written(coco_, folder_ + "/coco.json");
  const std::filesystem::path root(folder_);
  if (options_.webdataset) write_shards();
  if (!options_.yolo) return;
  for (YoloTask task : kYoloTasks) {
    const std::filesystem::path folder = root / "yolo" / to_string(task);
    for (const nlohmann::ordered_json& image : images_) {
      const std::filesystem::path picture = root / image["file_name"].get<std::string>();
      const std::filesystem::path link = folder / "images" / picture.filename();
      std::error_code ec;
      std::filesystem::create_hard_link(picture, link, ec);
      if (ec) std::filesystem::copy_file(picture, link, ec);  // another file system
      if (ec) {
        throw Error(ErrorCode::kIo, "--out", "'" + link.string() + "': " + ec.message());
      }
    }
    write_text((folder / "dataset.yaml").string(),
               yolo_dataset_yaml(task, names_, chosen_names(options_.keypoints),
                                 flip_places(options_.keypoints)));
  }
}

// Each image a sample, in frame order, its files in the shard one after another.
void CocoDataset::write_shards() const {
  const std::filesystem::path root(folder_);
  const std::filesystem::path samples = root / "webdataset" / "samples";
  TarShards shards((root / "webdataset").string(), 1000);
  for (const nlohmann::ordered_json& image : images_) {
    const std::string key = sample_key(image);
    shards.begin_sample();
    shards.add_file(key + ".png", (root / image["file_name"].get<std::string>()).string());
    shards.add_file(key + ".mask.png", (root / image["mask_file"].get<std::string>()).string());
    if (image.contains("depth_file")) {
      shards.add_file(key + ".depth.npy", (root / image["depth_file"].get<std::string>()).string());
    }
    shards.add_file(key + ".json", (samples / (key + ".json")).string());
  }
  shards.finish();
  std::filesystem::remove_all(samples);
}

}  // namespace finflex::pictures

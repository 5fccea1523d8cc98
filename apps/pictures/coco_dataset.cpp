#include "coco_dataset.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fish_keypoints.hpp"
#include "instance_masks.hpp"
#include "render/png16.hpp"

namespace finflex::pictures {

namespace {

// A keypoint counts as hidden when the surface seen at its pixel is this much nearer
// (metres) and belongs to something else.
constexpr double kOcclusionTolerance = 0.005;

std::string mask_name(std::size_t frame) {
  char name[48];
  std::snprintf(name, sizeof name, "masks/frame_%06zu.png", frame);
  return name;
}

nlohmann::ordered_json categories(const tank::SwimScene& scene) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t s = 0; s < scene.species().size(); ++s) {
    out.push_back({{"id", s + 1},
                   {"name", scene.species()[s].name},
                   {"supercategory", "fish"},
                   {"keypoints", {"snout", "tail_fork"}},
                   {"skeleton", {{1, 2}}}});
  }
  return out;
}

void require_written(const std::ofstream& stream, const std::string& path) {
  if (!stream) throw Error(ErrorCode::kIo, "--out", "'" + path + "': write failed");
}

}  // namespace

CocoDataset::CocoDataset(const std::string& folder, tank::SwimScene& scene,
                         const render::Camera& camera, int width, int height,
                         const nlohmann::ordered_json& info)
    : folder_(folder),
      scene_(scene),
      camera_(camera),
      width_(width),
      height_(height),
      camera_from_world_(render::camera_from_world(camera)) {
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
      truth.snout_slot = species.deformer->slot_of_vertex()[truth.landmarks.snout];
      truth.fork_slot = species.deformer->slot_of_vertex()[truth.landmarks.tail_fork];
    }
    species_.push_back(truth);
  }
  std::vector<std::size_t> per_species(scene.species().size(), 0);
  for (const tank::Fish& f : fish) {
    instance_of_fish_.push_back(per_species[f.species]++);
    fish_.push_back({f.species, f.length});
  }
  for (const tank::Species& species : scene.species()) names_.push_back(species.name);

  std::filesystem::create_directories(std::filesystem::path(folder) / "masks");
  const std::string path = (std::filesystem::path(folder) / "coco.json").string();
  coco_.open(path, std::ios::binary);
  nlohmann::ordered_json head;
  head["info"] = info;
  head["licenses"] = nlohmann::ordered_json::array();
  head["categories"] = categories(scene);
  const std::string text = head.dump();
  coco_ << text.substr(0, text.size() - 1) << ",\"annotations\":[";  // the object stays open
  require_written(coco_, path);
}

CocoDataset::FrameTruth CocoDataset::capture(std::size_t frame, double time_s,
                                             const std::string& image_file) {
  FrameTruth truth;
  truth.frame = frame;
  truth.time_s = time_s;
  truth.image_file = image_file;
  // Keypoints of every fish, from the engine's deformed vertices.
  truth.snouts.resize(scene_.species().size());
  truth.forks.resize(scene_.species().size());
  for (std::size_t s = 0; s < scene_.species().size(); ++s) {
    tank::Species& species = scene_.species()[s];
    if (!species.deformer) continue;
    cl::CommandQueue& queue = species.deformer->context().queue();
    const tank::BatchReading reading(species);
    truth.snouts[s] = read_slot_positions(queue, species.batch(), species_[s].snout_slot);
    truth.forks[s] = read_slot_positions(queue, species.batch(), species_[s].fork_slot);
  }
  return truth;
}

CocoDataset::FrameAnnotations CocoDataset::annotate(const FrameTruth& truth) const {
  const render::IdImage& ids = truth.ids;
  const auto pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  if (ids.width != width_ || ids.height != height_ || ids.ids.size() != pixels) {
    throw Error(ErrorCode::kInvalidArgument, "ids",
                "ids: an id pass of " + std::to_string(ids.width) + "x" +
                    std::to_string(ids.height) + " (" + std::to_string(ids.ids.size()) +
                    " ids) for a " + std::to_string(width_) + "x" + std::to_string(height_) +
                    " dataset");
  }
  const std::size_t image_id = truth.frame + 1;
  // The mask file: ids as they are (<= 65535).
  render::Image16 mask;
  mask.width = ids.width;
  mask.height = ids.height;
  mask.samples.assign(ids.ids.begin(), ids.ids.end());
  render::write_png16((std::filesystem::path(folder_) / mask_name(truth.frame)).string(), mask);

  FrameAnnotations out;
  const std::vector<InstanceMask> masks = instance_masks(ids);
  const render::PinholeIntrinsics k = render::pinhole_intrinsics(camera_, width_, height_);
  for (const InstanceMask& m : masks) {
    const std::size_t f = m.id - 1;
    const FishTruth& one = fish_[f];
    const std::size_t instance = instance_of_fish_[f];
    nlohmann::ordered_json keypoints = nlohmann::ordered_json::array();
    nlohmann::ordered_json camera_points = nlohmann::ordered_json::array();
    int labelled = 0;
    for (const glm::vec3& world :
         {truth.snouts[one.species][instance], truth.forks[one.species][instance]}) {
      const glm::dvec3 p = glm::dvec3(camera_from_world_ * glm::dvec4(glm::dvec3(world), 1.0));
      camera_points.push_back({p.x, p.y, p.z});
      const double u = k.fx * p.x / p.z + k.cx;
      const double v = k.fy * p.y / p.z + k.cy;
      const bool inside = p.z > double(camera_.near_plane) && u >= 0.0 && v >= 0.0 &&
                          u < double(width_) && v < double(height_);
      if (!inside) {
        keypoints.insert(keypoints.end(), {0.0, 0.0, 0});
        continue;
      }
      const std::size_t pixel = ids.index(static_cast<int>(u), static_cast<int>(v));
      const bool hidden =
          ids.ids[pixel] != m.id && double(ids.depth[pixel]) < p.z - kOcclusionTolerance;
      keypoints.insert(keypoints.end(), {u, v, hidden ? 1 : 2});
      ++labelled;
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
    annotation["keypoints_camera_m"] = camera_points;
    out.annotations.push_back(std::move(annotation));
  }
  out.image = {{"id", image_id},
               {"file_name", truth.image_file},
               {"mask_file", mask_name(truth.frame)},
               {"width", ids.width},
               {"height", ids.height},
               {"frame", truth.frame},
               {"time_s", truth.time_s},
               {"fish_in_tank", fish_.size()},
               {"fish_visible", masks.size()}};
  return out;
}

void CocoDataset::append(FrameAnnotations frame) {
  for (nlohmann::ordered_json& annotation : frame.annotations) {
    annotation["id"] = next_annotation_++;
    coco_ << (annotation_count() == 1 ? "\n" : ",\n") << annotation.dump();
  }
  images_.push_back(std::move(frame.image));
  require_written(coco_, folder_ + "/coco.json");
}

void CocoDataset::finish() {
  coco_ << "\n],\"images\":" << images_.dump() << "}\n";
  coco_.close();
  require_written(coco_, folder_ + "/coco.json");
}

}  // namespace finflex::pictures

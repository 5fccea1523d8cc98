#include "tank_scene.hpp"

#include "swim_scene.hpp"

namespace finflex::soak {
namespace {

constexpr double kFrameSeconds = 1.0 / 30.0;
constexpr std::uint64_t kSeed = 7;

class TankScene final : public SoakScene {
 public:
  TankScene(Context& context, const std::vector<RigSpecies>& species, std::size_t period,
            NormalMode normals)
      : context_(context), period_(period), normals_(normals) {
    for (const RigSpecies& s : species) {
      files_.push_back({s.mesh, s.rig});
      fish_ += s.instances;
    }
    build();
    description_ = "a swimming tank of " + std::to_string(fish_) + " fish (" +
                   std::to_string(files_.size()) + " species, " +
                   std::to_string(scene_->vertices_per_frame()) +
                   " vertices a frame), built again every period";
  }

  std::string describe() const override { return description_; }

  void enqueue(std::size_t frame) override {
    if (frame > 0 && frame % period_ == 0) build();
    scene_->enqueue_frame(kFrameSeconds);
  }

  std::uint64_t digest() override {
    std::uint64_t hash = kFnvOffset;
    for (tank::Species& species : scene_->species()) {
      if (!species.deformer) continue;
      const DeformedBatch<float> out = species.deformer->read(species.batch());
      hash = fnv1a(hash, out.positions.data(), out.positions.size() * sizeof(float));
      hash = fnv1a(hash, out.normals.data(), out.normals.size() * sizeof(float));
      hash = fnv1a(hash, out.tangents.data(), out.tangents.size() * sizeof(float));
    }
    return hash;
  }

 private:
  void build() {
    scene_.reset();  // the old tank goes before the new one is made
    scene_ = std::make_unique<tank::SwimScene>(context_, files_, fish_, tank::TankSettings{}, kSeed,
                                               normals_);
  }

  Context& context_;
  std::size_t period_;
  NormalMode normals_;
  std::vector<tank::SpeciesFiles> files_;
  std::size_t fish_ = 0;
  std::unique_ptr<tank::SwimScene> scene_;
  std::string description_;
};

}  // namespace

std::unique_ptr<SoakScene> make_tank_scene(Context& context, const std::vector<RigSpecies>& species,
                                           std::size_t period, NormalMode normals) {
  return std::make_unique<TankScene>(context, species, period, normals);
}

}  // namespace finflex::soak

#include "soak_scene.hpp"

#include <cmath>

namespace finflex::soak {
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < bytes; ++k) {
    hash ^= p[k];
    hash *= 1099511628211ull;
  }
  return hash;
}

namespace {

class RigBatchScene final : public SoakScene {
 public:
  RigBatchScene(Context& context, const std::vector<RigSpecies>& species, std::size_t period,
                NormalMode normals, RigPath path)
      : period_(period), normals_(normals), path_(path) {
    for (const RigSpecies& s : species) {
      const Mesh mesh = load_mesh(s.mesh);
      models_.push_back(
          std::make_unique<RiggedMesh>(mesh, resolve_rig(load_rig_file(s.rig), mesh)));
      deformers_.push_back(std::make_unique<ClDeformer>(context, *models_.back()));
      frame_.add(*deformers_.back(), s.instances);
      description_ += (description_.empty() ? "" : " + ") + std::to_string(s.instances) + " x " +
                      s.mesh + " (" + std::to_string(mesh.vertex_count()) + " vertices, " +
                      std::to_string(models_.back()->rig().components.size()) + " components)";
    }
  }

  std::string describe() const override { return description_; }

  void enqueue(std::size_t frame) override {
    const double phase = 2.0 * std::acos(-1.0) * double(frame % period_) / double(period_);
    for (std::size_t e = 0; e < frame_.size(); ++e) {
      RigParameters& values = frame_.parameters(e);
      const std::vector<RigParameter>& parameters = values.parameters();
      for (std::size_t i = 0; i < values.instance_count(); ++i) {
        for (std::size_t p = 0; p < parameters.size(); ++p) {
          for (std::size_t k = 0; k < parameters[p].count; ++k) {
            values.values()[i * values.values_per_instance() + parameters[p].offset + k] =
                static_cast<float>(0.9 * parameters[p].limit *
                                   std::sin(phase + 0.7 * double(i) + 1.3 * double(p + k)));
          }
        }
      }
    }
    frame_.enqueue(normals_, path_);
  }

  std::uint64_t digest() override {
    std::uint64_t hash = kFnvOffset;
    for (std::size_t e = 0; e < frame_.size(); ++e) {
      const DeformedBatch<float> out = deformers_[e]->read(frame_.batch(e));
      hash = fnv1a(hash, out.positions.data(), out.positions.size() * sizeof(float));
      hash = fnv1a(hash, out.normals.data(), out.normals.size() * sizeof(float));
      hash = fnv1a(hash, out.tangents.data(), out.tangents.size() * sizeof(float));
    }
    return hash;
  }

 private:
  std::size_t period_;
  NormalMode normals_;
  RigPath path_;
  std::vector<std::unique_ptr<RiggedMesh>> models_;
  std::vector<std::unique_ptr<ClDeformer>> deformers_;
  RigFrame frame_;  // after the deformers: destroyed first
  std::string description_;
};

}  // namespace

std::unique_ptr<SoakScene> make_rig_batch_scene(Context& context,
                                                const std::vector<RigSpecies>& species,
                                                std::size_t period, NormalMode normals,
                                                RigPath path) {
  return std::make_unique<RigBatchScene>(context, species, period, normals, path);
}

}  // namespace finflex::soak

// What the soak program runs frame after frame. A scene's inputs at frame f depend on
// f modulo its period only, so frames a period apart must give bit-identical outputs.
// RigBatchScene is a batch of instances of one or more rigged fish (one RigFrame
// entry each); another workload (a whole tank) plugs in by implementing SoakScene.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"

namespace finflex::soak {

class SoakScene {
 public:
  virtual ~SoakScene() = default;
  // One line: what runs (models, instances, vertices per frame).
  virtual std::string describe() const = 0;
  // Enqueues frame `frame` without waiting for it.
  virtual void enqueue(std::size_t frame) = 0;
  // Waits for the frames enqueued so far and hashes every output bit (FNV-1a 64).
  virtual std::uint64_t digest() = 0;
};

// FNV-1a (64 bits) of `bytes` bytes, continuing `hash` (start with kFnvOffset).
constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes);

struct RigSpecies {
  std::string mesh;  // a mesh file
  std::string rig;   // its rig file
  std::size_t instances = 0;
};

// Every species' instances in one RigFrame; instance i's parameter p at frame f is
// 0.9 of its limit times sin(2 pi (f mod period) / period + 0.7 i + 1.3 p).
std::unique_ptr<SoakScene> make_rig_batch_scene(Context& context,
                                                const std::vector<RigSpecies>& species,
                                                std::size_t period, NormalMode normals,
                                                RigPath path);

}  // namespace finflex::soak

// A tank of swimming fish on an OpenCL device: per species a model (mesh + swim rig),
// its swim driver and deformer and a batch of outputs in world space; every frame the
// tank steps on the host and each species' driver and deformation are enqueued.
// Shared by `finflex swim`, `finflex bench --swim` and the renderer.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "tank.hpp"

namespace finflex::tank {

// A species: a mesh file and its swim rig file.
struct SpeciesFiles {
  std::string mesh;
  std::string rig;
};

// "MESH:RIG" (the rig after the last ':'); kInvalidArgument naming `option` otherwise.
SpeciesFiles parse_species(const std::string& text, const std::string& option);

// A species' name: its rig file's name without ".rig.json" and "_swim".
std::string species_name(const SpeciesFiles& files);

// The bundled species under `data_dir`: Blub and the Barramundi with their swim rigs.
std::vector<SpeciesFiles> bundled_species(const std::string& data_dir);

struct Species {
  std::string name;  // the mesh file's stem
  SwimModel swim;    // its model: swim.model()
  std::unique_ptr<ClDeformer> deformer;
  std::unique_ptr<ClSwimDriver> driver;
  DeviceBatch batch;
  ClJob job;
  std::vector<SwimInput> inputs;  // this frame's, in the tank's order of its fish
};

// Host time of one frame's steps, and its kernels' events.
struct FrameWork {
  double simulation_seconds = 0.0;  // the tank's step and its swim inputs
  double enqueue_seconds = 0.0;     // the drivers' uploads and every launch
  std::vector<cl::Event> kernels;   // every kernel, in order (profiling)
};

class SwimScene {
 public:
  // Loads every species (errors name the species option and the file), splits `fish`
  // fish among them as evenly as possible, builds the tank, the drivers and the batches.
  SwimScene(Context& context, const std::vector<SpeciesFiles>& species, std::size_t fish,
            const TankSettings& settings, std::uint64_t seed, NormalMode normals,
            NormalFormat format = NormalFormat::kFloat32, const ClOptions& options = {});

  // One frame: the tank steps by dt, then each species' driver and deformation are
  // enqueued (nothing waits). With `profile`, every kernel's event goes to the result.
  FrameWork enqueue_frame(double dt, bool profile = false);

  Tank& tank() { return *tank_; }
  const Tank& tank() const { return *tank_; }
  std::vector<Species>& species() { return species_; }
  const std::vector<Species>& species() const { return species_; }
  // Vertices deformed per frame (all fish).
  std::size_t vertices_per_frame() const;

 private:
  Context& context_;
  std::vector<Species> species_;
  std::unique_ptr<Tank> tank_;
};

}  // namespace finflex::tank

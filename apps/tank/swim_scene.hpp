// A tank of swimming fish on an OpenCL device: per species a model (mesh + swim rig),
// its swim driver and deformer and its outputs in world space; every frame the tank
// steps on the host and each species' driver and deformation are enqueued.
// Shared by `finflex swim`, `finflex bench --swim` and the renderer.
//
// The outputs are FinFlex's planes in device buffers (ClDeformer::allocate) unless the
// caller gives a factory of its own: the renderer's (apps/pictures/fish_hand_off.hpp)
// has the deformation write GL buffers that it draws from.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "hall.hpp"

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

// Where one species' deformation goes every frame: its batch, and how a frame is
// enqueued into it.
class SpeciesOutputs {
 public:
  virtual ~SpeciesOutputs() = default;
  virtual DeviceBatch& batch() = 0;
  // Enqueues `job` (job.outputs is batch()) with `deformer`, as ClDeformer::enqueue.
  virtual cl::Event enqueue(ClDeformer& deformer, const ClJob& job,
                            std::vector<cl::Event>* kernel_events) = 0;
  // Host seconds the last enqueue spent handing the frame over to its consumer
  // (0: the batch is where the deformation wrote it).
  virtual double handoff_seconds() const { return 0.0; }
  // Whether enqueue waits for the device (a copy to another API): the frame's gate
  // (FrameGate) is then opened before it. No by default.
  virtual bool waits_for_device() const { return false; }
  // Blocking OpenCL reads of batch() between frames go between these (BatchReading):
  // outputs that another API owns between frames (GL buffers shared with OpenCL) are
  // lent to OpenCL meanwhile. Nothing by default.
  virtual void begin_reading() {}
  virtual void end_reading() {}
};

// FinFlex's planes in device buffers (ClDeformer::allocate): the scene's default.
class DeviceOutputs : public SpeciesOutputs {
 public:
  DeviceOutputs(const ClDeformer& deformer, std::size_t instances, NormalFormat format);
  DeviceBatch& batch() override { return batch_; }
  cl::Event enqueue(ClDeformer& deformer, const ClJob& job,
                    std::vector<cl::Event>* kernel_events) override;

 private:
  DeviceBatch batch_;
};

// Makes the outputs of species `species` (its deformer, its fish count, the normals'
// format), in world space, positions and normals at least.
using OutputsFactory = std::function<std::unique_ptr<SpeciesOutputs>(
    std::size_t species, ClDeformer& deformer, std::size_t instances, NormalFormat format)>;

// Levels of detail (finflex/level_deformer.hpp) for every species of a scene: each
// frame the fish its views see, at their levels, deformed into each level's outputs;
// no full-detail outputs.
struct SceneLevels {
  LevelOptions levels;        // make_detail_levels' (freeze_fins without value_bounds:
                              // each species' SwimModel::value_bounds)
  LevelChoiceOptions choice;  // level_rows empty: scene_level_rows
  // The hall's tank walls hide the fish behind them from the views (Hall::walls; a
  // caller whose views see the tanks otherwise, through refraction, clears them with
  // set_occluders).
  bool wall_occlusion = true;
};

// Each level's rows for `fish` fish: every level's outputs as large as the coarsest
// level's for 4 times the fish (level k: 4 fish x the coarsest level's vertices over
// level k's), at least 1,024 rows and at most `fish`. Fish past a level's rows are
// drawn at a coarser one (finflex/level_choice.hpp).
std::vector<std::size_t> scene_level_rows(const DetailLevels& levels, std::size_t fish);

// A species at its levels: the levels, their deformer and chooser, and each level's
// outputs and job (its list's fish of the species' driver buffers).
struct SpeciesLevels {
  explicit SpeciesLevels(DetailLevels made) : levels(std::move(made)) {}
  DetailLevels levels;
  std::unique_ptr<LevelDeformer> deformer;
  std::vector<std::unique_ptr<SpeciesOutputs>> outputs;
  std::vector<ClJob> jobs;
};

struct Species {
  std::string name;                      // the mesh file's stem
  SwimModel swim;                        // its model: swim.model()
  std::unique_ptr<ClDeformer> deformer;  // these three: only a species with fish
  std::unique_ptr<ClSwimDriver> driver;
  std::unique_ptr<SpeciesOutputs> outputs;
  ClJob job;
  // With SceneLevels: the levels (and no deformer, outputs or job above but the driver).
  std::unique_ptr<SpeciesLevels> leveled;

  DeviceBatch& batch() { return outputs->batch(); }
};

// Reads of a species' batch with OpenCL between frames (ClDeformer::read, ...) happen
// while one of these lives (SpeciesOutputs::begin_reading, end_reading).
class BatchReading {
 public:
  explicit BatchReading(Species& species);
  ~BatchReading();
  BatchReading(const BatchReading&) = delete;
  BatchReading& operator=(const BatchReading&) = delete;

 private:
  SpeciesOutputs* outputs_;
};

// Host time of one frame's steps, and its kernels' events.
struct FrameWork {
  double simulation_seconds = 0.0;  // the tank's step and its swim inputs
  double enqueue_seconds = 0.0;     // the drivers' uploads and every launch (and what
                                    // the hand-off waits for, when it waits)
  double driver_seconds = 0.0;      // of which the drivers' (their staging areas taken,
                                    // inputs checked and uploaded, kernels launched)
  double handoff_seconds = 0.0;     // the outputs' hand-off (SpeciesOutputs)
  std::vector<cl::Event> kernels;   // every kernel, in order (profiling)
};

class SwimScene {
 public:
  // Loads every species (errors name the species option and the file), splits `fish`
  // fish among them as evenly as possible, builds the hall (one tank, or several), the
  // drivers and the outputs (`outputs`, or DeviceOutputs when it is empty: with
  // `levels`, each level's of every species, for its rows). With levels, set_views
  // before the first frame.
  SwimScene(Context& context, const std::vector<SpeciesFiles>& species, std::size_t fish,
            const HallSettings& settings, std::uint64_t seed, NormalMode normals,
            NormalFormat format = NormalFormat::kFloat32, const ClTuning& options = {},
            const OutputsFactory& outputs = {},
            const std::optional<SceneLevels>& levels = std::nullopt);

  // The views that choose the levels (1 to kMaxLevelViews; LevelChooser::enqueue checks
  // them each frame).
  void set_views(const std::vector<LevelView>& views) { views_ = views; }
  const std::vector<LevelView>& views() const { return views_; }
  // The walls that hide fish from the views, for every species' choice (with levels:
  // the hall's walls when SceneLevels::wall_occlusion, else none).
  void set_occluders(const std::vector<WallOccluder>& walls);
  bool has_levels() const;

  // One frame: the tank steps by dt, then each species' driver and deformation are
  // enqueued behind a FrameGate, opened once all are (or before outputs that wait for
  // the device); nothing waits, unless the outputs' hand-off does. With `profile`,
  // every kernel's event goes to the result.
  FrameWork enqueue_frame(double dt, bool profile = false);
  // The same in two steps, so that the next frame's step can run on another thread
  // while this frame is drawn: the hall's step (its seconds), then the frame of the
  // hall as it stands (its simulation time: writing the inputs).
  double step_hall(double dt);
  FrameWork enqueue_stepped_frame(double dt, bool profile = false);

  // Writes species `species`' swim inputs of this frame, one per fish of that species,
  // into `staged` (its driver's staging memory, ClSwimDriver::staged_inputs).
  using InputWriter = std::function<void(std::size_t species, SwimInput* staged)>;
  // One frame from inputs the caller writes (a simulation of its own, recorded steps):
  // the tank does not step. Writing them is the frame's simulation time.
  FrameWork enqueue_frame(double dt, const InputWriter& write_inputs, bool profile = false);

  Hall& hall() { return *hall_; }
  const Hall& hall() const { return *hall_; }
  std::vector<Species>& species() { return species_; }
  const std::vector<Species>& species() const { return species_; }
  // Vertices deformed per frame: all fish's, or with levels those of the last frame's
  // lists (read from the device: waits for the queue).
  std::size_t vertices_per_frame() const;
  // With levels, the last frame's fish per level of species s (read from the device),
  // and those in view at no level for want of rows.
  struct LevelCounts {
    std::vector<std::size_t> per_level;
    std::size_t demoted = 0;  // drawn at a coarser level than their error asked for
    std::size_t undrawn = 0;
  };
  LevelCounts level_counts(std::size_t species) const;

 private:
  Context& context_;
  std::vector<Species> species_;
  std::unique_ptr<Hall> hall_;
  std::vector<LevelView> views_;
};

}  // namespace finflex::tank

#include "swim_scene.hpp"

#include <algorithm>
#include <filesystem>
#include "finflex/internal/cl_tuning.hpp"

namespace finflex::tank {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DeviceOutputs::DeviceOutputs(const ClDeformer& deformer, std::size_t instances, NormalFormat format)
    : batch_(deformer.allocate(instances, format)) {}

cl::Event DeviceOutputs::enqueue(ClDeformer& deformer, const ClJob& job,
                                 std::vector<cl::Event>* kernel_events) {
  return deformer.enqueue(job, kernel_events);
}

BatchReading::BatchReading(Species& species) : outputs_(species.outputs.get()) {
  if (outputs_ != nullptr) outputs_->begin_reading();
}

BatchReading::~BatchReading() {
  if (outputs_ != nullptr) outputs_->end_reading();
}

std::string species_name(const SpeciesFiles& files) {
  // "data/rigs/blub_swim.rig.json" -> "blub".
  std::string name = std::filesystem::path(files.rig).filename().string();
  for (const char* suffix : {".json", ".rig", "_swim"}) {
    const std::string end(suffix);
    if (name.size() > end.size() && name.compare(name.size() - end.size(), end.size(), end) == 0)
      name.erase(name.size() - end.size());
  }
  return name;
}

SpeciesFiles parse_species(const std::string& text, const std::string& option) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "' is not MESH:RIG (a mesh file and its swim rig file)");
  }
  return {text.substr(0, colon), text.substr(colon + 1)};
}

std::vector<SpeciesFiles> bundled_species(const std::string& data_dir) {
  return {
      {data_dir + "/blub/fish.obj", data_dir + "/rigs/blub_swim.rig.json"},
      {data_dir + "/barramundi/BarramundiFish.gltf", data_dir + "/rigs/barramundi_swim.rig.json"}};
}

std::vector<std::size_t> scene_level_rows(const DetailLevels& levels, std::size_t fish) {
  const double coarsest = double(levels.level(levels.size() - 1).vertex_count);
  std::vector<std::size_t> rows;
  for (const DetailLevel& level : levels.levels()) {
    const double share = 4.0 * double(fish) * coarsest / double(level.vertex_count);
    rows.push_back(std::min(fish, std::max<std::size_t>(1024, std::size_t(std::ceil(share)))));
  }
  return rows;
}

namespace {

// The species' outputs for `instances` instances of `deformer`'s model: the caller's
// factory's, or FinFlex's planes on the device.
std::unique_ptr<SpeciesOutputs> make_outputs(const OutputsFactory& factory, std::size_t species,
                                             ClDeformer& deformer, std::size_t instances,
                                             NormalFormat format) {
  std::unique_ptr<SpeciesOutputs> made =
      factory ? factory(species, deformer, instances, format)
              : std::make_unique<DeviceOutputs>(deformer, instances, format);
  if (!made) {
    throw Error(ErrorCode::kInvalidArgument, "outputs",
                "outputs: the factory made none for species " + std::to_string(species));
  }
  return made;
}

}  // namespace

SwimScene::SwimScene(Context& context, const std::vector<SpeciesFiles>& files, std::size_t fish,
                     const HallSettings& settings, std::uint64_t seed, NormalMode normals,
                     NormalFormat format, const ClTuning& options, const OutputsFactory& outputs,
                     const std::optional<SceneLevels>& levels)
    : context_(context) {
  if (files.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "species", "species: at least one is needed");
  }
  // Every model first: a bad file is found before any device work.
  std::vector<std::size_t> counts;
  species_.reserve(files.size());
  for (std::size_t s = 0; s < files.size(); ++s) {
    const std::string at = "species[" + std::to_string(s) + "]";
    try {
      const Mesh mesh = load_mesh(files[s].mesh);
      SwimModel swim(RiggedMesh(mesh, resolve_rig(load_rig_file(files[s].rig), mesh)));
      species_.push_back(
          Species{species_name(files[s]), std::move(swim), nullptr, nullptr, nullptr, {}, nullptr});
    } catch (const Error& e) {
      throw Error(e.code(), at, at + ": " + e.what());
    }
    counts.push_back(fish / files.size() + (s < fish % files.size() ? 1 : 0));
  }
  hall_ = std::make_unique<Hall>(settings, counts, seed);
  for (std::size_t s = 0; s < species_.size(); ++s) {
    Species& sp = species_[s];
    if (counts[s] == 0) continue;
    sp.driver = std::make_unique<ClSwimDriver>(context_, sp.swim, hall_->lengths(s),
                                               std::vector<float>{}, options.table_items);
    ClDeviceInputs inputs{&sp.driver->parameter_buffer(), &sp.driver->placement_buffer(),
                          sp.driver->derived_buffer()};
    if (levels) {
      LevelOptions level_options = levels->levels;
      if (level_options.freeze_fins && level_options.value_bounds.empty())
        level_options.value_bounds = sp.swim.value_bounds();  // what the driver gives the fins
      auto lv = std::make_unique<SpeciesLevels>(make_detail_levels(sp.swim.model(), level_options));
      LevelChoiceOptions choice = levels->choice;
      if (choice.level_rows.empty()) choice.level_rows = scene_level_rows(lv->levels, counts[s]);
      lv->deformer =
          std::make_unique<LevelDeformer>(context_, lv->levels, counts[s], choice, format, false);
      for (std::size_t k = 0; k < lv->levels.size(); ++k) {
        ClDeformer& deformer = lv->deformer->deformer(k);
        lv->outputs.push_back(
            make_outputs(outputs, s, deformer, lv->deformer->chooser().rows(k), format));
        lv->jobs.push_back(lv->deformer->job(k, inputs, counts[s], normals));
        lv->jobs.back().outputs = &lv->outputs.back()->batch();
      }
      if (levels->wall_occlusion) lv->deformer->chooser().set_occluders(hall_->walls());
      sp.leveled = std::move(lv);
      continue;
    }
    sp.deformer = std::make_unique<ClDeformer>(context_, sp.swim.model(), options);
    sp.outputs = make_outputs(outputs, s, *sp.deformer, counts[s], format);
    sp.job.instances = counts[s];
    sp.job.device.parameters = &sp.driver->parameter_buffer();
    sp.job.device.placements = &sp.driver->placement_buffer();
    sp.job.device.derived = sp.driver->derived_buffer();  // null: rig_prepare runs
    sp.job.normals = normals;
    sp.job.outputs = &sp.outputs->batch();
  }
}

FrameWork SwimScene::enqueue_frame(double dt, bool profile) {
  const double step_seconds = step_hall(dt);
  FrameWork work = enqueue_stepped_frame(dt, profile);
  work.simulation_seconds += step_seconds;
  return work;
}

double SwimScene::step_hall(double dt) {
  const auto start = std::chrono::steady_clock::now();
  hall_->step(dt);
  return seconds_since(start);
}

FrameWork SwimScene::enqueue_stepped_frame(double dt, bool profile) {
  // The hall writes the inputs straight into the drivers' staging memory.
  return enqueue_frame(
      dt, [this](std::size_t species, SwimInput* staged) { hall_->inputs(species, staged); },
      profile);
}

FrameWork SwimScene::enqueue_frame(double dt, const InputWriter& write_inputs, bool profile) {
  FrameWork work;
  const auto start = std::chrono::steady_clock::now();
  // Taking the staging area is the driver's host time, writing into it the simulation's.
  double staging_seconds = 0.0;
  for (std::size_t s = 0; s < species_.size(); ++s) {
    if (!species_[s].driver) continue;
    const auto staging_start = std::chrono::steady_clock::now();
    SwimInput* staged = species_[s].driver->staged_inputs();
    staging_seconds += seconds_since(staging_start);
    write_inputs(s, staged);
  }
  work.simulation_seconds = seconds_since(start) - staging_seconds;
  work.driver_seconds = staging_seconds;
  if (has_levels() && views_.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "views",
                "views: a scene with levels of detail needs its views (set_views)");
  }
  const auto enqueue_start = std::chrono::steady_clock::now();
  std::vector<cl::Event> events;
  FrameGate gate(context_);  // the frame goes to the device once all of it is enqueued
  for (std::size_t s = 0; s < species_.size(); ++s) {
    Species& sp = species_[s];
    if (!sp.driver) continue;
    const auto driver_start = std::chrono::steady_clock::now();
    const cl::Event driven = sp.driver->enqueue_staged(static_cast<float>(dt), gate.wait_list());
    work.driver_seconds += seconds_since(driver_start);
    if (profile) work.kernels.push_back(driven);
    if (sp.leveled) {
      SpeciesLevels& lv = *sp.leveled;
      lv.deformer->chooser().enqueue(sp.driver->placement_buffer(), sp.driver->fish_count(), views_,
                                     nullptr, profile ? &events : nullptr);
      if (profile) work.kernels.insert(work.kernels.end(), events.begin(), events.end());
      for (std::size_t k = 0; k < lv.outputs.size(); ++k) {
        if (lv.outputs[k]->waits_for_device()) gate.open();
        lv.outputs[k]->enqueue(lv.deformer->deformer(k), lv.jobs[k], profile ? &events : nullptr);
        work.handoff_seconds += lv.outputs[k]->handoff_seconds();
        if (profile) work.kernels.insert(work.kernels.end(), events.begin(), events.end());
      }
      continue;
    }
    if (sp.outputs->waits_for_device()) gate.open();
    sp.outputs->enqueue(*sp.deformer, sp.job, profile ? &events : nullptr);
    work.handoff_seconds += sp.outputs->handoff_seconds();
    if (profile) work.kernels.insert(work.kernels.end(), events.begin(), events.end());
  }
  gate.open();
  work.enqueue_seconds =
      std::max(0.0, seconds_since(enqueue_start) - work.handoff_seconds) + staging_seconds;
  return work;
}

void SwimScene::set_occluders(const std::vector<WallOccluder>& walls) {
  for (Species& sp : species_) {
    if (sp.leveled) sp.leveled->deformer->chooser().set_occluders(walls);
  }
}

bool SwimScene::has_levels() const {
  for (const Species& sp : species_) {
    if (sp.leveled) return true;
  }
  return false;
}

SwimScene::LevelCounts SwimScene::level_counts(std::size_t species) const {
  LevelCounts out;
  const Species& sp = species_.at(species);
  if (!sp.leveled) return out;
  const LevelChooser::Choice choice = sp.leveled->deformer->chooser().read();
  for (std::size_t k = 0; k < choice.lists.size(); ++k) {
    out.per_level.push_back(choice.lists[k].size());
    for (std::uint32_t fish : choice.lists[k]) out.demoted += choice.level_of[fish] < int(k);
  }
  out.undrawn = choice.undrawn;
  return out;
}

std::size_t SwimScene::vertices_per_frame() const {
  std::size_t vertices = 0;
  for (std::size_t s = 0; s < species_.size(); ++s) {
    const Species& sp = species_[s];
    if (!sp.driver) continue;
    if (!sp.leveled) {
      vertices += sp.swim.model().vertex_count() * sp.driver->fish_count();
      continue;
    }
    const LevelCounts counts = level_counts(s);
    for (std::size_t k = 0; k < counts.per_level.size(); ++k)
      vertices += counts.per_level[k] * sp.leveled->levels.level(k).vertex_count;
  }
  return vertices;
}

}  // namespace finflex::tank

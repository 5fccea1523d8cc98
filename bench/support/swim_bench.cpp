#include "swim_bench.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace finflex::bench {
namespace {

// The swim inputs of the tank's next `steps` steps of dt, species by species.
std::vector<std::vector<std::vector<SwimInput>>> record_tank_steps(tank::SwimScene& scene,
                                                                   std::size_t steps, double dt) {
  std::vector<std::vector<std::vector<SwimInput>>> recorded(steps);
  for (auto& step : recorded) {
    scene.hall().step(dt);
    step.resize(scene.species().size());
    for (std::size_t s = 0; s < step.size(); ++s) scene.hall().inputs(s, step[s]);
  }
  return recorded;
}

}  // namespace

Measured measure_swim(Context& context, const std::string& mesh, const std::string& rig,
                      const FrameBenchSettings& settings, std::unique_ptr<tank::SwimScene>& scene) {
  const OutputsChoice planes;
  if (settings.outputs.layout != planes.layout || settings.outputs.order != planes.order ||
      settings.outputs.previous || settings.outputs.host) {
    throw Error(ErrorCode::kInvalidArgument, "outputs",
                "outputs: the swim writes the default planes");
  }
  const std::size_t instances = settings.instances;
  const std::size_t frames = settings.frames;
  tank::TankSettings tank_settings;
  const double scale = std::max(1.0, std::cbrt(double(instances) / 1000.0));
  tank_settings.diameter *= scale;
  tank_settings.depth *= scale;
  scene = std::make_unique<tank::SwimScene>(context, std::vector<tank::SpeciesFiles>{{mesh, rig}},
                                            instances, tank_settings, 1, settings.normals,
                                            settings.format, settings.options);
  tank::Species& species = scene->species().front();
  Measured measured;
  measured.swim = true;
  std::vector<double> enqueue, driver;  // per timed frame, the tank's step excluded
  constexpr double kFrameSeconds = 1.0 / 30.0;
  // The untimed first frame and the timed ones (time_frames).
  const std::size_t most_steps = std::clamp<std::size_t>(
      kRecordedSwimBytes / (instances * sizeof(SwimInput)), 1, kRecordedSwimFrames);
  const std::size_t steps = settings.recorded_swim_inputs ? std::min(frames + 1, most_steps) : 0;
  const auto recorded = record_tank_steps(*scene, steps, kFrameSeconds);
  std::size_t frame = 0;
  auto enqueue_frame = [&]() {
    if (recorded.empty()) return scene->enqueue_frame(kFrameSeconds, true);
    const auto& step = recorded[frame++ % recorded.size()];
    return scene->enqueue_frame(
        kFrameSeconds,
        [&step](std::size_t s, SwimInput* staged) {
          std::copy(step[s].begin(), step[s].end(), staged);
        },
        true);
  };
  const std::size_t output_vertices = species.batch().shape.plane_stride;
  measured.shape = kernel_shape(*species.deformer, species.batch(), settings.normals);
  measured.write_only =
      fastest_write_only(context, species.batch(), output_vertices, measured.shape, frames);
  measured.times = time_frames(
      frames, [](std::size_t) {},
      [&](std::vector<cl::Event>& events, bool timed) {
        const tank::FrameWork work = enqueue_frame();
        if (timed) {
          enqueue.push_back(work.enqueue_seconds);
          driver.push_back(work.driver_seconds);
        }
        events = work.kernels;
      },
      frames_ahead(context),
      write_reference(context, species.batch(), output_vertices, measured.write_only));
  // time_frames timed the whole call on the host, the tank's step included.
  measured.times.host = enqueue;
  measured.host_driver_seconds = driver;
  measured.what = std::string("swim ") + to_string(species.deformer->automatic_path());
  measured.batch = &species.batch();
  measured.vertices = species.swim.model().vertex_count();
  measured.output_vertices = output_vertices;
  measured.bytes_per_vertex = species.batch().shape.bytes_per_vertex();
  return measured;
}

}  // namespace finflex::bench

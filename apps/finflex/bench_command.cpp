// finflex bench: frames of a batch on one device, timed by OpenCL profiling events,
// next to a write-only kernel of the same NDRange and output planes (the device's
// write bandwidth, measured in the same run).
//
//   finflex bench --mesh PATH --instances N --frames F [--mode paper|exact]
//                 [--normals rotate|jacobian] [--normal-format float32|half]
//                 [--rig RIG.json [--path fused|passes]] [--device NAME] [--json]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "finflex/cli_errors.hpp"
#include "finflex/commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct BenchOptions {
  std::string mesh;
  std::size_t instances = 1000;
  std::size_t frames = 100;
  std::string mode = "paper";
  std::string normals = "rotate";
  std::string normal_format = "float32";
  std::string rig;
  std::string path = "auto";
  std::string device;
  bool json = false;
};

// Device seconds from the start of `first` to the end of `last`.
double device_seconds(const cl::Event& first, const cl::Event& last) {
  check_cl(last.wait(), "clWaitForEvents");
  return static_cast<double>(last.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                             first.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
         1e-9;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct FrameTimes {
  std::vector<double> device;  // kernel time per frame
  std::vector<double> host;    // wall time of the enqueue call (checks, upload, launches)
};

// Runs one warm-up frame (PoCL compiles per work-group shape), then `frames` timed ones.
// `prepare(frame)` sets the frame's parameters (not timed: that is the application's
// animation); `enqueue(kernels)` enqueues the frame and returns its kernels' events
// (timed on the host, then on the device).
template <typename Prepare, typename Enqueue>
FrameTimes time_frames(std::size_t frames, Prepare prepare, Enqueue enqueue) {
  FrameTimes times;
  std::vector<cl::Event> kernels;
  prepare(0);
  enqueue(kernels);
  device_seconds(kernels.front(), kernels.back());
  for (std::size_t f = 1; f <= frames; ++f) {
    prepare(f);
    const auto start = std::chrono::steady_clock::now();
    enqueue(kernels);
    const auto end = std::chrono::steady_clock::now();
    times.host.push_back(std::chrono::duration<double>(end - start).count());
    times.device.push_back(device_seconds(kernels.front(), kernels.back()));
  }
  return times;
}

// The write-only kernel over the batch's planes: the faster of the device's instances
// per work-item (the bend's) and 4 (the rig's on GPUs).
double write_only_median(Context& context, DeviceBatch& batch, std::size_t frames) {
  double fastest = 0.0;
  for (std::size_t per_item : {std::size_t{0}, std::size_t{4}}) {
    const FrameTimes times = time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events) {
          events.assign(1, enqueue_write_only(context, batch, per_item));
        });
    const double seconds = median(times.device);
    fastest = fastest == 0.0 ? seconds : std::min(fastest, seconds);
  }
  return fastest;
}

// Parameter p of instance i at frame f: half the range, a travelling phase.
float swing(double limit, std::size_t i, std::size_t p, std::size_t f) {
  return static_cast<float>(0.5 * limit * std::sin(0.05 * double(f) + 0.1 * double(i) + double(p)));
}

int run_bench(const BenchOptions& options) {
  try {
    if (options.instances == 0)
      throw Error(ErrorCode::kInvalidArgument, "--instances", "--instances must be > 0");
    if (options.frames == 0)
      throw Error(ErrorCode::kInvalidArgument, "--frames", "--frames must be > 0");
    const NormalMode normals = parse_normal_mode(options.normals, "--normals");
    const NormalFormat format = parse_normal_format(options.normal_format, "--normal-format");
    const Mesh mesh = load_mesh(options.mesh);
    Context context(options.device);
    DeviceBatch batch;
    FrameTimes times;
    std::string what;
    std::size_t passes = 1;
    double scratch_records = 0.0;  // float32 vertex records through scratch, per slot
    if (options.rig.empty()) {
      const BendSettings settings{parse_bend_mode(options.mode, "--mode"), normals};
      const LocalMesh local = make_local_mesh(mesh, find_body_frame(mesh));
      ClDeformer deformer(context, local);
      batch = deformer.allocate(options.instances, format);
      std::vector<float> m(options.instances);
      const double limit = max_abs_m(local.x_max);
      times = time_frames(
          options.frames,
          [&](std::size_t f) {
            for (std::size_t i = 0; i < m.size(); ++i) m[i] = swing(limit, i, 0, f);
          },
          [&](std::vector<cl::Event>& events) {
            events.assign(1, deformer.enqueue(m, settings, batch));
          });
      what = std::string("bend ") + to_string(settings.mode);
    } else {
      const RigPath path = parse_rig_path(options.path, "--path");
      const Rig rig = resolve_rig(load_rig_file(options.rig), mesh);
      ClRigDeformer deformer(context, mesh, rig);
      batch = deformer.allocate(options.instances, format);
      RigParameters values(rig, options.instances);
      const std::vector<double> limits = rig_param_limits(rig);
      const RigPath chosen = path == RigPath::kAuto ? deformer.automatic_path() : path;
      passes = chosen == RigPath::kPasses ? deformer.pass_count() : 1;
      scratch_records = chosen == RigPath::kPasses ? deformer.scratch_records_per_slot() : 0.0;
      times = time_frames(
          options.frames,
          [&](std::size_t f) {
            for (std::size_t i = 0; i < options.instances; ++i) {
              for (std::size_t p = 0; p < rig.params.size(); ++p) {
                values.values()[i * rig.params.size() + p] = swing(limits[p], i, p, f);
              }
            }
          },
          [&](std::vector<cl::Event>& events) {
            deformer.enqueue(values, normals, batch, chosen, false, nullptr, &events);
          });
      what = std::string("rig ") + to_string(chosen);
    }
    const double seconds = median(times.device);
    const double write_seconds = write_only_median(context, batch, options.frames);
    const double vertices = double(mesh.vertex_count()) * double(options.instances);
    const double bytes_per_vertex = double(batch.layout.bytes_per_vertex());
    const double written =
        double(batch.layout.plane_stride) * double(options.instances) * bytes_per_vertex;

    nlohmann::ordered_json result;
    result["device"] = context.description().device_name;
    result["mesh"] = options.mesh;
    result["deformation"] = what;
    result["normals"] = to_string(normals);
    result["normal_format"] = to_string(format);
    result["vertices"] = mesh.vertex_count();
    result["instances"] = options.instances;
    result["frames"] = options.frames;
    result["passes"] = passes;
    result["seconds_per_frame_median"] = seconds;
    result["seconds_per_frame_min"] = *std::min_element(times.device.begin(), times.device.end());
    result["vertices_per_second"] = vertices / seconds;
    result["output_bytes_per_second"] = written / seconds;
    // Multi-pass: intermediate results go through float32 scratch sets (12 B per
    // attribute each way).
    const double scratch_record_bytes = 12.0 * (batch.layout.tangents ? 3.0 : 2.0);
    result["moved_bytes_per_vertex"] = bytes_per_vertex + scratch_record_bytes * scratch_records;
    result["write_bandwidth_bytes_per_second"] = written / write_seconds;
    result["write_fraction"] = write_seconds / seconds;
    result["host_enqueue_seconds_median"] = median(times.host);
    if (options.json) {
      std::printf("%s\n", result.dump().c_str());
    } else {
      std::printf("%s\n", result.dump(2).c_str());
    }
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("bench", error.what());
  }
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* bench =
      app.add_subcommand("bench", "Time frames of a batch against the write bandwidth");
  bench->add_option("--mesh", options->mesh, "Mesh to deform")->required();
  bench->add_option("--instances", options->instances, "Instances per frame")
      ->capture_default_str();
  bench->add_option("--frames", options->frames, "Timed frames (after one warm-up)")
      ->capture_default_str();
  bench->add_option("--mode", options->mode, "paper or exact (without --rig)")
      ->capture_default_str();
  bench->add_option("--normals", options->normals, "rotate or jacobian")->capture_default_str();
  bench->add_option("--normal-format", options->normal_format, "float32 or half")
      ->capture_default_str();
  bench->add_option("--rig", options->rig, "Rig file: time the rig instead of the single bend");
  bench->add_option("--path", options->path, "With --rig: auto, fused or passes")
      ->capture_default_str();
  bench->add_option("--device", options->device, "OpenCL device: 'P:D' or a name substring");
  bench->add_flag("--json", options->json, "One JSON object on one line");
  return [options] { return run_bench(*options); };
}

}  // namespace finflex::cli

// finflex bench: frames of a batch on one device, timed by OpenCL profiling events,
// next to a write-only kernel of the same NDRange and output planes (the device's
// write bandwidth, measured in the same run).
//
//   finflex bench --mesh PATH --instances N --frames F [--mode paper|exact]
//                 [--normals rotate|jacobian] [--normal-format float32|half]
//                 [--rig RIG.json [--path fused|passes]] [--device NAME] [--json]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "reference_kernels.hpp"
#include "timing.hpp"

namespace finflex::cli {
namespace {

struct BenchOptions {
  std::string mesh;
  std::string instances = "1000";
  std::string frames = "100";
  std::string mode = "paper";
  std::string normals = "rotate";
  std::string normal_format = "float32";
  std::string rig;
  std::string path = "auto";
  std::string device;
  bool json = false;
};

// The write-only kernel over the batch's planes: the faster of the deformer's
// instances per work-item and 4 (the rig kernels' on GPUs).
double write_only_median(Context& context, DeviceBatch& batch, std::size_t per_item,
                         std::size_t frames) {
  double fastest = 0.0;
  for (std::size_t per : {per_item, std::size_t{4}}) {
    const bench::FrameTimes times = bench::time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events) {
          events.assign(1, bench::enqueue_write_only(context, batch, per));
        });
    const double seconds = bench::median(times.device);
    fastest = fastest == 0.0 ? seconds : std::min(fastest, seconds);
  }
  return fastest;
}

// Parameter p of instance i at frame f: half the range, a travelling phase.
float swing(double limit, std::size_t i, std::size_t p, std::size_t f) {
  return static_cast<float>(0.5 * limit * std::sin(0.05 * double(f) + 0.1 * double(i) + double(p)));
}

// Bench keeps every frame's times (host and device): a million frames take 16 MB.
constexpr std::size_t kMaxFrames = 1000000;

struct BenchCounts {
  std::size_t instances = 0;
  std::size_t frames = 0;
};

BenchCounts check_bench(const BenchOptions& options) {
  BenchCounts counts;
  counts.instances = parse_count(options.instances, "--instances", 1, kMaxDeviceInstances,
                                 "the kernels count instances in 32 bits");
  counts.frames =
      parse_count(options.frames, "--frames", 1, kMaxFrames, "bench keeps every frame's time");
  parse_normal_mode(options.normals, "--normals");
  parse_normal_format(options.normal_format, "--normal-format");
  parse_rig_path(options.path, "--path");
  check_input_file("--mesh", options.mesh, mesh_extensions());
  if (options.rig.empty()) {
    parse_bend_mode(options.mode, "--mode");
  } else {
    check_input_file("--rig", options.rig);
  }
  return counts;
}

// After check_bench: the device, then the files.
int run_bench(const BenchOptions& options) {
  try {
    const BenchCounts counts = check_bench(options);
    const NormalMode normals = parse_normal_mode(options.normals, "--normals");
    const NormalFormat format = parse_normal_format(options.normal_format, "--normal-format");
    Context context(options.device);
    const Mesh mesh = for_option("--mesh", [&] { return load_mesh(options.mesh); });
    const RiggedMesh model =
        options.rig.empty()
            ? RiggedMesh::single_bend(mesh, find_body_frame(mesh),
                                      parse_bend_mode(options.mode, "--mode"))
            : RiggedMesh(
                  mesh, resolve_rig(for_option("--rig", [&] { return load_rig_file(options.rig); }),
                                    mesh));
    const RigPath path = parse_rig_path(options.path, "--path");
    ClDeformer deformer(context, model);
    DeviceBatch batch = deformer.allocate(counts.instances, format);
    RigParameters values(model, counts.instances);
    const Rig& rig = model.rig();
    ClJob job;
    job.model = &model;
    job.parameters = values.view();
    job.normals = normals;
    job.path = path;
    job.outputs = &batch;
    const RigPath chosen = path == RigPath::kAuto ? deformer.automatic_path() : path;
    const bool passes_path = chosen == RigPath::kPasses && !deformer.uses_single_bend_kernel();
    const std::size_t passes = passes_path ? deformer.pass_count() : 1;
    // Float32 vertex records through scratch, per slot (multi-pass only).
    const double scratch_records = passes_path ? deformer.scratch_records_per_slot() : 0.0;
    const bench::FrameTimes times = bench::time_frames(
        counts.frames,
        [&](std::size_t f) {
          for (std::size_t i = 0; i < counts.instances; ++i) {
            for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
              const RigParameter& parameter = rig.parameters[p];
              for (std::size_t k = 0; k < parameter.count; ++k) {
                values.values()[i * values.values_per_instance() + parameter.offset + k] =
                    swing(parameter.limit, i, p + k, f);
              }
            }
          }
        },
        [&](std::vector<cl::Event>& events) { deformer.enqueue(job, &events); });
    const std::string what = options.rig.empty() ? std::string("bend ") + options.mode
                                                 : std::string("rig ") + to_string(chosen);
    const double seconds = bench::median(times.device);
    const double write_seconds =
        write_only_median(context, batch, deformer.instances_per_item(format), counts.frames);
    const double vertices = double(mesh.vertex_count()) * double(counts.instances);
    const double bytes_per_vertex = double(batch.layout.bytes_per_vertex());
    const double written =
        double(batch.layout.plane_stride) * double(counts.instances) * bytes_per_vertex;

    nlohmann::ordered_json result;
    result["device"] = context.description().device_name;
    result["mesh"] = options.mesh;
    result["deformation"] = what;
    result["normals"] = to_string(normals);
    result["normal_format"] = to_string(format);
    result["vertices"] = mesh.vertex_count();
    result["instances"] = counts.instances;
    result["frames"] = counts.frames;
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
    result["host_enqueue_seconds_median"] = bench::median(times.host);
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
  bench->add_option("--instances", options->instances, "Instances per frame (1 to 2^32 - 1)")
      ->capture_default_str();
  bench->add_option("--frames", options->frames, "Timed frames after one warm-up (1 to 10^6)")
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
  return {[options] { check_bench(*options); }, [options] { return run_bench(*options); }};
}

}  // namespace finflex::cli

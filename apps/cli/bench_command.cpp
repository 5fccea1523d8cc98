// finflex bench: frames of a batch on one device, timed by OpenCL profiling events,
// next to a write-only kernel of the same outputs (the device's write bandwidth,
// measured in the same run: the fastest of its shapes; on CPUs that shape also runs
// after every frame, write_fraction_interleaved the median of the frames' own ratios).
//
//   finflex bench --mesh PATH --instances N --frames F [--mode paper|exact]
//                 [--normals rotate|jacobian] [--normal-format float32|half]
//                 [--rig RIG.json [--path fused|passes] [--swim [--swim-inputs recorded|live]]]
//                 [--layout planes|interleaved|compact|snorm|arrays] [--order slots|mesh]
//                 [--previous] [--host] [--per-item N] [--table-items N] [--lanes 0|1|8|16|32]
//                 [--stores auto|plain|streaming] [--device NAME] [--json]
//
// --layout, --order, --previous: the outputs in that layout (docs/handoff.md), the
// write-only kernel writing the same layout. --host: the outputs in host memory
// (ClDeformer::bind_host), and the time to map each finished frame for the host.
//
// --swim: a tank of N swimming fish (the swim rig given by --rig): per frame the swim
// driver kernel, the rig's prepare kernel and the deformation with world placement,
// timed from the driver's start to the deformation's end; the host time is the
// enqueue (inputs gathered and uploaded, launches), the tank's simulation excluded.
// --swim-inputs: recorded (default) steps the tank for the timed frames before they
// run (a ring of at most kRecordedSwimFrames steps, replayed in turn) and each frame
// copies its step's inputs into the drivers' staging memory, so the device is fed as
// by an application whose simulation keeps ahead of it; live steps the tank inside the
// frame loop, and the device waits for the host whenever a step takes longer than a
// frame (10,000 fish: a millisecond or more against 0.7 ms of kernels on an H200).
//
// On GPUs the frames run ahead (the next one enqueued before this one is waited for,
// JSON "frames_ahead": true), as in an application's frame loop; on CPUs one by one.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_layouts.hpp"
#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "huge_page_settings.hpp"
#include "reference_kernels.hpp"
#include "swim_scene.hpp"
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
  std::string per_item = "0";
  std::string table_items = "0";
  std::string lanes = "0";
  std::string stores = "auto";
  std::string dispatch = "auto";
  bool swim = false;
  std::string swim_inputs;  // --swim only; empty: recorded
  std::string layout = "planes";
  std::string order = "slots";
  bool previous = false;
  bool host = false;
  std::string device;
  bool json = false;
};

// The write-only kernel's fastest shape for a batch, and its median frame time.
struct WriteOnlyShape {
  std::size_t per_item = 1;
  std::size_t lanes = 1;
  bool streaming = false;
  double seconds = 0.0;
};

// What a benchmark measured, with the write-only kernel it is compared with.
struct Measured {
  std::string what;
  std::size_t passes = 1;
  double scratch_records = 0.0;  // float32 vertex records through scratch, per slot
  bench::FrameTimes times;
  DeviceBatch* batch = nullptr;
  std::size_t per_item = 1;
  std::size_t lanes = 1;
  bool streaming = false;            // streaming stores (with lanes)
  std::size_t vertices = 0;          // per instance
  std::size_t output_vertices = 0;   // the outputs' (slots or mesh vertices)
  std::size_t bytes_per_vertex = 0;  // written per output vertex and instance
  // --host: the map that hands each frame to the host (ClDeformer::map_host) after the
  // kernels completed, host wall time per frame.
  std::vector<double> host_map_seconds;
  // --swim: of the host's enqueue, the driver's part (inputs checked, copied, uploaded,
  // the driver kernel launched).
  std::vector<double> host_driver_seconds;
  // The write-only kernel's fastest shape, timed on its own before the frames; on CPUs
  // also after every frame (times.reference).
  WriteOnlyShape write_only;
};

// --host: frames whose kernels are waited for, then mapped for the host and timed:
// on CPU devices the kernels wrote the caller's memory (no copy), on GPUs the driver
// copies the frame into it.
std::vector<double> time_host_maps(ClDeformer& deformer, ClJob& job, std::size_t frames) {
  std::vector<double> seconds;
  for (std::size_t f = 0; f <= frames; ++f) {
    std::vector<cl::Event> events;
    deformer.enqueue(job, &events);
    check_cl(cl::Event::waitForEvents(events), "clWaitForEvents");
    const auto start = std::chrono::steady_clock::now();
    deformer.map_host(*job.outputs);
    const auto end = std::chrono::steady_clock::now();
    if (f > 0) seconds.push_back(std::chrono::duration<double>(end - start).count());
  }
  deformer.unmap_host(*job.outputs);
  return seconds;
}

// Frames run ahead (bench::time_frames) on GPUs: the host enqueues the next frame
// while the device runs this one, as an application's frame loop does; on CPUs each
// frame is waited for (the host's work would take the kernels' cores).
bool frames_ahead(Context& context) { return context.description().is_gpu(); }

// The write-only kernel of a shape through the batch's layout.
cl::Event enqueue_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                             const WriteOnlyShape& shape) {
  return bench::enqueue_write_only(context, batch, vertices, shape.per_item,
                                   bench::WriteValues::kDeviceDefault, shape.lanes,
                                   shape.streaming);
}

// The write-only kernel through the batch's layout: the fastest of the deformer's
// instances per work-item and 4 (the rig kernels' on GPUs), each with one lane and,
// when the deformer has more for this batch (FinFlex's float32 planes), with its lanes
// (vector stores, kernels/cpu/lane_outputs.cl), streaming and plain.
WriteOnlyShape fastest_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                                  std::size_t per_item, std::size_t lanes, std::size_t frames) {
  std::vector<WriteOnlyShape> shapes;
  for (std::size_t per : {per_item, std::size_t{4}}) {
    shapes.push_back({per, 1, false, 0.0});
    if (lanes > 1) shapes.insert(shapes.end(), {{per, lanes, true, 0.0}, {per, lanes, false, 0.0}});
  }
  WriteOnlyShape fastest;
  for (WriteOnlyShape& shape : shapes) {
    const bench::FrameTimes times = bench::time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events) {
          events.assign(1, enqueue_write_only(context, batch, vertices, shape));
        },
        frames_ahead(context));
    shape.seconds = bench::median(times.device);
    if (fastest.seconds == 0.0 || shape.seconds < fastest.seconds) fastest = shape;
  }
  return fastest;
}

// On CPUs, whose frames are waited for one by one, the write-only kernel's fastest shape
// runs after every frame too (bench::time_frames' reference): on a shared machine a
// frame's time drifts from run to run by a fifth or more, and a frame and the write-only
// kernel right after it see the machine in the same state. None on GPUs (frames ahead).
std::function<cl::Event()> write_reference(Context& context, DeviceBatch& batch,
                                           std::size_t vertices, const WriteOnlyShape& shape) {
  if (frames_ahead(context)) return {};
  return [&context, &batch, vertices, shape] {
    return enqueue_write_only(context, batch, vertices, shape);
  };
}

// Value k of a table parameter (a spine's angles) for instance i at frame f: a smooth
// travelling wave of 0.3 rad, far from folding.
float table_wave(std::size_t count, std::size_t i, std::size_t k, std::size_t f) {
  return static_cast<float>(
      0.3 * std::sin(6.0 * double(k) / double(count) - 0.2 * double(f) + 0.1 * double(i)));
}

// Parameter p of instance i at frame f: half the range, a travelling phase.
float swing(double limit, std::size_t i, std::size_t p, std::size_t f) {
  return static_cast<float>(0.5 * limit * std::sin(0.05 * double(f) + 0.1 * double(i) + double(p)));
}

// The whole-body bend or a rig, its parameters animated on the host.
struct DeformBench {
  std::unique_ptr<RiggedMesh> model;
  std::unique_ptr<ClDeformer> deformer;
  HostMemory host;
  DeviceBatch batch;
};

// --per-item, --table-items, --lanes, --stores and --dispatch: the backend's choices, for
// experiments.
ClTuning cl_options(const BenchOptions& options) {
  ClTuning cl;
  cl.instances_per_item =
      parse_count(options.per_item, "--per-item", 0, 64, "instances per work-item");
  cl.table_items =
      parse_count(options.table_items, "--table-items", 0, 64, "work-items per instance's table");
  if ((cl.table_items & (cl.table_items - 1)) != 0) {
    throw Error(ErrorCode::kInvalidArgument, "--table-items",
                "--table-items '" + options.table_items +
                    "' is not a power of two (expected 0: the device's, 1, 2, 4, ... 64)");
  }
  cl.lanes = parse_count(options.lanes, "--lanes", 0, 32, "vertex slots per work-item");
  if (cl.lanes != 0 && cl.lanes != 1 && cl.lanes != 8 && cl.lanes != 16 && cl.lanes != 32) {
    throw Error(ErrorCode::kInvalidArgument, "--lanes",
                "--lanes '" + options.lanes +
                    "' is not a number of lanes (expected 0: the device's, 1, 8, 16 or 32)");
  }
  if (options.stores == "plain") {
    cl.stores = OutputStores::kPlain;
  } else if (options.stores == "streaming") {
    cl.stores = OutputStores::kStreaming;
  } else if (options.stores != "auto") {
    throw Error(ErrorCode::kInvalidArgument, "--stores",
                "--stores '" + options.stores +
                    "' is not a kind of store (expected auto, plain or streaming)");
  }
  if (options.dispatch == "per-component") {
    cl.dispatch = RigDispatch::kPerComponent;
  } else if (options.dispatch == "by-path-shape") {
    cl.dispatch = RigDispatch::kByPathShape;
  } else if (options.dispatch != "auto") {
    throw Error(ErrorCode::kInvalidArgument, "--dispatch",
                "--dispatch '" + options.dispatch +
                    "' is not a dispatch (expected auto, per-component or by-path-shape)");
  }
  return cl;
}

Measured measure_deform(const BenchOptions& options, const Mesh& mesh, Context& context,
                        std::size_t instances, std::size_t frames, NormalMode normals,
                        NormalFormat format, DeformBench& bench) {
  bench.model = std::make_unique<RiggedMesh>(
      options.rig.empty()
          ? RiggedMesh::single_bend(mesh, find_body_frame(mesh),
                                    parse_bend_mode(options.mode, "--mode"))
          : RiggedMesh(mesh,
                       resolve_rig(for_option("--rig", [&] { return load_rig_file(options.rig); }),
                                   mesh)));
  const RiggedMesh& model = *bench.model;
  const RigPath path = parse_rig_path(options.path, "--path");
  bench.deformer = std::make_unique<ClDeformer>(context, model, cl_options(options));
  ClDeformer& deformer = *bench.deformer;
  BenchLayout layout =
      bench_layout(deformer, format, options.layout, options.order, options.previous);
  layout.host = options.host;
  bench.batch = make_bench_batch(deformer, instances, layout, bench.host);
  RigParameters values(model, instances);
  ClJob job;
  job.model = &model;
  job.parameters = values.view();
  job.normals = normals;
  job.path = path;
  job.outputs = &bench.batch;
  const RigPath chosen = path == RigPath::kAuto ? deformer.automatic_path() : path;
  const bool passes_path = chosen == RigPath::kPasses && !deformer.uses_single_bend_kernel();
  Measured measured;
  measured.passes = passes_path ? internal::pass_count(deformer) : 1;
  measured.scratch_records = passes_path ? internal::scratch_records_per_slot(deformer) : 0.0;
  const Rig& rig = model.rig();
  measured.write_only =
      fastest_write_only(context, bench.batch, layout.vertices,
                         internal::instances_per_item(deformer, layout.layout, normals),
                         internal::lanes(deformer, layout.layout), frames);
  measured.times = bench::time_frames(
      frames,
      [&](std::size_t f) {
        for (std::size_t i = 0; i < instances; ++i) {
          for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
            const RigParameter& parameter = rig.parameters[p];
            for (std::size_t k = 0; k < parameter.count; ++k) {
              values.values()[i * values.values_per_instance() + parameter.offset + k] =
                  parameter.count == 1 ? swing(parameter.limit, i, p, f)
                                       : table_wave(parameter.count, i, k, f);
            }
          }
        }
      },
      [&](std::vector<cl::Event>& events) { deformer.enqueue(job, &events); },
      frames_ahead(context),
      write_reference(context, bench.batch, layout.vertices, measured.write_only));
  if (options.host) measured.host_map_seconds = time_host_maps(deformer, job, frames);
  measured.what = options.rig.empty() ? std::string("bend ") + options.mode
                                      : std::string("rig ") + to_string(chosen);
  measured.batch = &bench.batch;
  measured.per_item = internal::instances_per_item(deformer, layout.layout, normals);
  measured.lanes = internal::lanes(deformer, layout.layout);
  measured.streaming = internal::streams_outputs(deformer, bench.batch);
  measured.vertices = mesh.vertex_count();
  measured.output_vertices = layout.vertices;
  measured.bytes_per_vertex = layout.bytes_per_vertex;
  return measured;
}

// --swim-inputs recorded: the tank's steps replayed in turn, at most 64 and at most
// 256 MiB of inputs (64 steps of 10,000 fish: 18 MB).
constexpr std::size_t kRecordedSwimFrames = 64;
constexpr std::size_t kRecordedSwimBytes = std::size_t{256} << 20;

// Whether --swim-inputs (given with --swim) says recorded, the default.
bool parse_swim_inputs(const std::string& text, bool swim) {
  if (!text.empty() && !swim) {
    throw Error(ErrorCode::kInvalidArgument, "--swim-inputs",
                "--swim-inputs '" + text + "' needs --swim");
  }
  if (text.empty() || text == "recorded") return true;
  if (text == "live") return false;
  throw Error(ErrorCode::kInvalidArgument, "--swim-inputs",
              "--swim-inputs '" + text + "' is not recorded or live");
}

// The swim inputs of the tank's next `steps` steps of dt, species by species.
std::vector<std::vector<std::vector<SwimInput>>> record_tank_steps(tank::SwimScene& scene,
                                                                   std::size_t steps, double dt) {
  std::vector<std::vector<std::vector<SwimInput>>> recorded(steps);
  for (auto& step : recorded) {
    scene.tank().step(dt);
    step.resize(scene.species().size());
    for (std::size_t s = 0; s < step.size(); ++s) scene.tank().inputs(s, step[s]);
  }
  return recorded;
}

// A tank of swimming fish of one species, the tank scaled to keep the density of
// 1,000 fish in the default tank.
Measured measure_swim(const BenchOptions& options, Context& context, std::size_t instances,
                      std::size_t frames, NormalMode normals, NormalFormat format,
                      std::unique_ptr<tank::SwimScene>& scene) {
  if (options.rig.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--swim", "--swim needs --rig (a swim rig)");
  }
  if (options.layout != "planes" || options.order != "slots" || options.previous || options.host) {
    throw Error(ErrorCode::kInvalidArgument, "--swim",
                "--swim writes the default planes (no --layout, --order, --previous or --host)");
  }
  tank::TankSettings settings;
  const double scale = std::max(1.0, std::cbrt(double(instances) / 1000.0));
  settings.diameter *= scale;
  settings.depth *= scale;
  scene = std::make_unique<tank::SwimScene>(
      context, std::vector<tank::SpeciesFiles>{{options.mesh, options.rig}}, instances, settings, 1,
      normals, format, cl_options(options));
  tank::Species& species = scene->species().front();
  Measured measured;
  std::vector<double> enqueue, driver;  // per timed frame, the tank's step excluded
  constexpr double kFrameSeconds = 1.0 / 30.0;
  // The untimed first frame and the timed ones (time_frames).
  const std::size_t most_steps = std::clamp<std::size_t>(
      kRecordedSwimBytes / (instances * sizeof(SwimInput)), 1, kRecordedSwimFrames);
  const std::size_t steps =
      parse_swim_inputs(options.swim_inputs, true) ? std::min(frames + 1, most_steps) : 0;
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
  const std::size_t output_vertices = species.batch().layout.plane_stride;
  measured.write_only = fastest_write_only(
      context, species.batch(), output_vertices,
      internal::instances_per_item(*species.deformer, species.deformer->planes_layout(1, format),
                                   normals),
      internal::lanes(*species.deformer, species.batch().outputs), frames);
  measured.times = bench::time_frames(
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
  measured.per_item = internal::instances_per_item(
      *species.deformer, species.deformer->planes_layout(1, format), normals);
  measured.lanes = internal::lanes(*species.deformer, species.batch().outputs);
  measured.streaming = internal::streams_outputs(*species.deformer, species.batch());
  measured.vertices = species.swim.model().vertex_count();
  measured.output_vertices = output_vertices;
  measured.bytes_per_vertex = species.batch().layout.bytes_per_vertex();
  return measured;
}

// Bench keeps every frame's times (host and device): a million frames take 16 MB.
constexpr std::size_t kMaxFrames = 1000000;

struct BenchCounts {
  std::size_t instances = 0;
  std::size_t frames = 0;
};

// Every option that can be checked before a file is read or the device opened.
BenchCounts check_bench(const BenchOptions& options) {
  BenchCounts counts;
  counts.instances = parse_count(options.instances, "--instances", 1, kMaxDeviceInstances,
                                 "the kernels count instances in 32 bits");
  counts.frames =
      parse_count(options.frames, "--frames", 1, kMaxFrames, "bench keeps every frame's time");
  parse_normal_mode(options.normals, "--normals");
  parse_normal_format(options.normal_format, "--normal-format");
  parse_rig_path(options.path, "--path");
  parse_swim_inputs(options.swim_inputs, options.swim);
  cl_options(options);  // --per-item, --table-items, --lanes, --stores, --dispatch
  check_bench_layout(options.layout, options.order);
  check_input_file("--mesh", options.mesh, mesh_extensions());
  if (options.rig.empty()) {
    parse_bend_mode(options.mode, "--mode");
    if (options.swim) {
      throw Error(ErrorCode::kInvalidArgument, "--swim", "--swim needs --rig (a swim rig)");
    }
  } else {
    check_input_file("--rig", options.rig);
  }
  return counts;
}

// After check_bench: the files, then the device.
int run_bench(const BenchOptions& options) {
  try {
    const BenchCounts counts = check_bench(options);
    const std::size_t instances = counts.instances;
    const std::size_t frames = counts.frames;
    const NormalMode normals = parse_normal_mode(options.normals, "--normals");
    const NormalFormat format = parse_normal_format(options.normal_format, "--normal-format");
    const Mesh mesh = for_option("--mesh", [&] { return load_mesh(options.mesh); });
    Context context(options.device);
    DeformBench deform;
    std::unique_ptr<tank::SwimScene> scene;
    std::vector<double> hosts;
    const Measured m =
        options.swim
            ? measure_swim(options, context, instances, frames, normals, format, scene)
            : measure_deform(options, mesh, context, instances, frames, normals, format, deform);
    const double seconds = bench::median(m.times.device);
    // The write-only kernel's fastest shape timed on its own, and (CPUs) each frame's
    // own ratio to that shape run right after it.
    const double write_seconds = m.write_only.seconds;
    std::vector<double> frame_fractions;
    for (std::size_t f = 0; f < m.times.reference.size(); ++f) {
      frame_fractions.push_back(m.times.reference[f] / m.times.device[f]);
    }
    const double vertices = double(m.vertices) * double(instances);
    const BatchLayout& layout = m.batch->layout;
    const double bytes_per_vertex = double(m.bytes_per_vertex);
    const double written = double(m.output_vertices) * double(instances) * bytes_per_vertex;

    nlohmann::ordered_json result;
    result["device"] = context.description().device_name;
    result["mesh"] = options.mesh;
    result["deformation"] = m.what;
    result["normals"] = to_string(normals);
    result["normal_format"] = to_string(format);
    result["layout"] = options.layout;
    result["order"] = options.order;
    result["previous_positions"] = options.previous;
    result["vertices"] = m.vertices;
    result["instances"] = instances;
    result["frames"] = frames;
    result["passes"] = m.passes;
    result["seconds_per_frame_median"] = seconds;
    result["seconds_per_frame_min"] =
        *std::min_element(m.times.device.begin(), m.times.device.end());
    result["vertices_per_second"] = vertices / seconds;
    result["output_bytes_per_second"] = written / seconds;
    // Multi-pass: intermediate results go through float32 scratch sets (12 B per
    // attribute each way).
    const double scratch_record_bytes = 12.0 * (layout.tangents ? 3.0 : 2.0);
    result["moved_bytes_per_vertex"] = bytes_per_vertex + scratch_record_bytes * m.scratch_records;
    result["write_bandwidth_bytes_per_second"] = written / write_seconds;
    result["write_fraction"] = write_seconds / seconds;
    result["write_fraction_interleaved"] = nullptr;
    if (!frame_fractions.empty()) {
      result["write_fraction_interleaved"] = bench::median(frame_fractions);
    }
    result["host_enqueue_seconds_median"] = bench::median(m.times.host);
    if (options.swim) {
      result["host_driver_seconds_median"] = bench::median(m.host_driver_seconds);
      result["swim_inputs"] = parse_swim_inputs(options.swim_inputs, true) ? "recorded" : "live";
    }
    result["host_outputs"] = options.host;
    if (options.host) {
      const double map_seconds = bench::median(m.host_map_seconds);
      result["host_map_seconds_median"] = map_seconds;
      result["host_map_bytes_per_second"] = written / map_seconds;
    }
    // Each kernel of a frame, in launch order (swim: the driver, rig_prepare, then the
    // deformation's).
    result["kernel_seconds_median"] = m.times.kernel_medians();
    result["instances_per_item"] = m.per_item;
    result["lanes"] = m.lanes;
    result["streaming_stores"] = m.streaming;
    result["frames_ahead"] = frames_ahead(context);
    // What puts the host's memory in huge pages (CPU devices' buffers are host memory),
    // and how much of it the process holds in them after the frames.
    const std::optional<std::uint64_t> huge_bytes = process_huge_page_bytes();
    result["huge_pages"] = {
        {"transparent", transparent_huge_pages()},
        {"glibc_malloc_hugetlb", glibc_malloc_hugetlb()},
        {"process_bytes", huge_bytes ? nlohmann::ordered_json(*huge_bytes) : nullptr}};
    std::printf("%s\n", options.json ? result.dump().c_str() : result.dump(2).c_str());
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
  bench
      ->add_option("--per-item", options->per_item,
                   "Instances per work-item (0: the device's choice)")
      ->capture_default_str();
  bench
      ->add_option("--table-items", options->table_items,
                   "Work-items per instance's table (spine records, swim driver): a power of "
                   "two up to 64 (0: the device's choice)")
      ->capture_default_str();
  bench
      ->add_option("--lanes", options->lanes,
                   "Vertex slots per work-item: 1, 8, 16, 32 (0: the device's; on CPUs FinFlex's "
                   "planes are stored as vectors, other layouts lane by lane)")
      ->capture_default_str();
  bench
      ->add_option("--stores", options->stores,
                   "With lanes: auto (streaming when the outputs exceed the cache), plain or "
                   "streaming")
      ->capture_default_str();
  bench->add_option("--dispatch", options->dispatch, "auto, per-component or by-path-shape")
      ->capture_default_str();
  bench
      ->add_option("--layout", options->layout,
                   "Output layout: planes, interleaved, compact (octahedral normals), snorm or "
                   "arrays (each attribute its own packed array)")
      ->capture_default_str();
  bench->add_option("--order", options->order, "Output vertex order: slots or mesh")
      ->capture_default_str();
  bench->add_flag("--previous", options->previous, "Also write previous-frame positions");
  bench->add_flag("--host", options->host,
                  "Outputs in host memory (bind_host); also time mapping each frame for the host");
  bench->add_flag("--swim", options->swim,
                  "With a swim rig: a tank of swimming fish (driver, deformation, placement)");
  bench->add_option("--swim-inputs", options->swim_inputs,
                    "With --swim: recorded (default; the tank's steps run before the timed "
                    "frames) or live (the tank steps inside the frame loop)");
  bench->add_option("--device", options->device, "OpenCL device: 'P:D' or a name substring");
  bench->add_flag("--json", options->json, "One JSON object on one line");
  return {[options] { check_bench(*options); }, [options] { return run_bench(*options); }};
}

}  // namespace finflex::cli

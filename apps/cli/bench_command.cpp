// finflex bench: frames of a batch on one device against the write bandwidth, the
// harness of bench/support (frame_bench.hpp, swim_bench.hpp); this file turns the
// options into its settings and the library's errors into the options that gave them.
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
// --swim: a tank of N swimming fish (the swim rig given by --rig); --swim-inputs
// recorded (default) or live (swim_bench.hpp).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "farm_bench.hpp"
#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "frame_bench.hpp"
#include "level_flags.hpp"
#include "swim_bench.hpp"

namespace finflex::cli {
namespace {

struct BenchOptions {
  std::string mesh;
  std::string instances;  // empty: 1,000, or 100,000 with --farm
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
  bool farm = false;
  std::string tanks = "16";
  std::string levels = "6";  // the farm's: 6 levels of half the triangles (benchmarks.md)
  std::string triangle_ratio = "0.5";
  bool freeze_fins = true;
  bool wall_occlusion = true;
  std::string pixel_budget = "1";
  std::string layout = "planes";
  std::string order = "slots";
  bool previous = false;
  bool host = false;
  std::string device;
  bool json = false;
};

// Bench keeps every frame's times (host and device): a million frames take 16 MB.
constexpr std::size_t kMaxFrames = 1000000;

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

// --per-item, --table-items, --lanes, --stores and --dispatch: the backend's choices, for
// experiments. The counts' values are the library's to check (ClDeformer).
ClTuning cl_options(const BenchOptions& options) {
  ClTuning cl;
  cl.instances_per_item =
      parse_count(options.per_item, "--per-item", 0, 64, "instances per work-item");
  cl.table_items =
      parse_count(options.table_items, "--table-items", 0, 64, "work-items per instance's table");
  cl.lanes = parse_count(options.lanes, "--lanes", 0, 32, "vertex slots per work-item");
  cl.stores = parse_choice<OutputStores>(options.stores, "--stores", "a kind of store",
                                         {{"auto", OutputStores::kAuto},
                                          {"plain", OutputStores::kPlain},
                                          {"streaming", OutputStores::kStreaming}},
                                         "auto, plain or streaming");
  cl.dispatch = parse_choice<RigDispatch>(options.dispatch, "--dispatch", "a dispatch",
                                          {{"auto", RigDispatch::kAuto},
                                           {"per-component", RigDispatch::kPerComponent},
                                           {"by-path-shape", RigDispatch::kByPathShape}},
                                          "auto, per-component or by-path-shape");
  return cl;
}

// --layout, --order, --previous and --host.
bench::OutputsChoice outputs_choice(const BenchOptions& options) {
  bench::OutputsChoice outputs;
  const std::optional<bench::LayoutKind> layout = bench::layout_named(options.layout);
  if (!layout) {
    throw Error(ErrorCode::kInvalidArgument, "--layout",
                "--layout '" + options.layout + "' is not a layout (expected " +
                    bench::layout_names() + ")");
  }
  outputs.layout = *layout;
  outputs.order = parse_choice<VertexOrder>(
      options.order, "--order", "an order",
      {{"slots", VertexOrder::kSlots}, {"mesh", VertexOrder::kMesh}}, "slots or mesh");
  outputs.previous = options.previous;
  outputs.host = options.host;
  return outputs;
}

bench::FarmSettings check_farm(const BenchOptions& options,
                               const bench::FrameBenchSettings& settings);

// Every option that can be checked before a file is read or the device opened, as the
// harness's settings.
bench::FrameBenchSettings check_bench(const BenchOptions& options) {
  bench::FrameBenchSettings settings;
  const std::string instances = !options.instances.empty() ? options.instances
                                : options.farm             ? "100000"
                                                           : "1000";
  settings.instances = parse_count(instances, "--instances", 1, kMaxDeviceInstances,
                                   "the kernels count instances in 32 bits");
  settings.frames =
      parse_count(options.frames, "--frames", 1, kMaxFrames, "bench keeps every frame's time");
  settings.normals = parse_normal_mode(options.normals, "--normals");
  settings.format = parse_normal_format(options.normal_format, "--normal-format");
  settings.path = parse_rig_path(options.path, "--path");
  settings.recorded_swim_inputs = parse_swim_inputs(options.swim_inputs, options.swim);
  settings.options = cl_options(options);
  settings.outputs = outputs_choice(options);
  check_input_file("--mesh", options.mesh, mesh_extensions());
  if (options.rig.empty()) {
    parse_bend_mode(options.mode, "--mode");
    if (options.swim) {
      throw Error(ErrorCode::kInvalidArgument, "--swim", "--swim needs --rig (a swim rig)");
    }
  } else {
    check_input_file("--rig", options.rig);
  }
  if (options.swim && (options.layout != "planes" || options.order != "slots" || options.previous ||
                       options.host)) {
    throw Error(ErrorCode::kInvalidArgument, "--swim",
                "--swim writes the default planes (no --layout, --order, --previous or --host)");
  }
  if (options.farm) check_farm(options, settings);
  return settings;
}

// --farm: a swim rig, the default planes, and the hall's and the levels' options.
bench::FarmSettings check_farm(const BenchOptions& options,
                               const bench::FrameBenchSettings& settings) {
  if (options.rig.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--farm", "--farm needs --rig (a swim rig)");
  }
  if (options.swim || options.layout != "planes" || options.order != "slots" || options.previous ||
      options.host) {
    throw Error(ErrorCode::kInvalidArgument, "--farm",
                "--farm swims the fish itself and writes the default planes (no --swim, "
                "--layout, --order, --previous or --host)");
  }
  bench::FarmSettings farm;
  farm.fish = settings.instances;
  farm.frames = settings.frames;
  farm.normals = settings.normals;
  farm.format = settings.format;
  farm.tanks = parse_count(options.tanks, "--tanks", 1, 1024, "tanks in the hall");
  if (farm.fish < farm.tanks) {
    throw Error(ErrorCode::kInvalidArgument, "--instances",
                "--instances '" + std::to_string(farm.fish) + "': every one of the " +
                    std::to_string(farm.tanks) + " tanks needs a fish");
  }
  farm.levels = parse_level_options(options.levels, options.triangle_ratio, options.freeze_fins);
  farm.choice.pixel_budget = parse_positive(options.pixel_budget, "--pixel-budget");
  farm.wall_occlusion = options.wall_occlusion;
  return farm;
}

// The library's message for `error` said of the option that gave the value, as typed:
// "tuning.lanes: 4 is not ..." as "--lanes '4' is not ...", "instances = N needs ..."
// as "--instances 'N': N needs ...".
std::string said_of_option(const Error& error, const std::string& option,
                           const std::string& typed) {
  std::string rest = error.what();
  if (rest.compare(0, error.field().size(), error.field()) == 0) {
    rest.erase(0, error.field().size());
    for (const std::string separator : {": ", " = "}) {
      if (rest.compare(0, separator.size(), separator) == 0) rest.erase(0, separator.size());
    }
  }
  const std::string named = option + " '" + typed + "'";
  const std::size_t digits = rest.find_first_not_of("0123456789");
  if (digits > 0 && digits != std::string::npos && rest.compare(digits, 4, " is ") == 0) {
    return named + rest.substr(digits);
  }
  return named + ": " + rest;
}

// Runs `operation`; a finflex::Error of a field that one of bench's options gave (the
// backend's options, the instance count) comes out naming that option.
template <typename Operation>
auto with_option_names(const BenchOptions& options, Operation operation) {
  try {
    return operation();
  } catch (const Error& error) {
    const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> fields = {
        {"tuning.lanes", {"--lanes", options.lanes}},
        {"tuning.table_items", {"--table-items", options.table_items}},
        {"items_per_fish", {"--table-items", options.table_items}},
        {"tuning.instances_per_item", {"--per-item", options.per_item}},
        {"instances", {"--instances", options.instances}}};
    for (const auto& [field, option] : fields) {
      if (error.field() == field) {
        throw Error(error.code(), option.first, said_of_option(error, option.first, option.second));
      }
    }
    throw;
  }
}

// After check_bench: the files, then the device.
int run_bench(const BenchOptions& options) {
  try {
    const bench::FrameBenchSettings settings = check_bench(options);
    const Mesh mesh = for_option("--mesh", [&] { return load_mesh(options.mesh); });
    Context context(options.device);
    if (options.farm) {
      const nlohmann::ordered_json farm = with_option_names(options, [&] {
        return bench::measure_farm(context, options.mesh, options.rig,
                                   check_farm(options, settings));
      });
      std::printf("%s\n", options.json ? farm.dump().c_str() : farm.dump(2).c_str());
      return kExitSuccess;
    }
    std::unique_ptr<RiggedMesh> model;
    bench::DeformBench deform;
    std::unique_ptr<tank::SwimScene> scene;
    const bench::Measured measured = with_option_names(options, [&] {
      if (options.swim)
        return bench::measure_swim(context, options.mesh, options.rig, settings, scene);
      model = std::make_unique<RiggedMesh>(
          options.rig.empty()
              ? RiggedMesh::single_bend(mesh, find_body_frame(mesh),
                                        parse_bend_mode(options.mode, "--mode"))
              : RiggedMesh(mesh, resolve_rig(for_option("--rig",
                                                        [&] { return load_rig_file(options.rig); }),
                                             mesh)));
      return bench::measure_deform(context, *model, options.rig.empty() ? options.mode : "",
                                   settings, deform);
    });
    const nlohmann::ordered_json result =
        bench::frame_bench_record(context, options.mesh, settings, measured);
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
  bench->add_flag("--farm", options->farm,
                  "With a swim rig: a farm hall (100,000 fish by default) with levels of detail "
                  "and culling, side by side with the same hall at full detail");
  bench->add_option("--tanks", options->tanks, "With --farm: tanks in the hall (rows of 4)")
      ->capture_default_str();
  bench->add_option("--levels", options->levels, "With --farm: levels of detail (1 to 8)")
      ->capture_default_str();
  bench
      ->add_option("--triangle-ratio", options->triangle_ratio,
                   "With --farm: each level's share of the finer level's triangles")
      ->capture_default_str();
  bench->add_flag(kFreezeFinsFlag, options->freeze_fins,
                  "With --farm: one more level after the coarsest, its fins frozen (only the "
                  "body's stages), its error bound added (default on)");
  bench->add_flag(kWallOcclusionFlag, options->wall_occlusion,
                  "With --farm: fish behind other tanks' walls are culled (default on)");
  bench
      ->add_option("--pixel-budget", options->pixel_budget,
                   "With --farm: the error a level may show, in pixels of a 1920x1080 image")
      ->capture_default_str();
  bench->add_option("--device", options->device, "OpenCL device: 'P:D' or a name substring");
  bench->add_flag("--json", options->json, "One JSON object on one line");
  return {[options] { check_bench(*options); }, [options] { return run_bench(*options); }};
}

}  // namespace finflex::cli

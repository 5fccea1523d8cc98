// The finflex command line as other tools call it: what it writes, against the
// library's own reference and device runs of the same values; exit codes, the
// one-line error message naming the problem, and no output file on any error.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "support/deform.hpp"
#include "support/run_cli.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

using test::fish;
using test::line_count;
using test::read_text;
using test::run_cli;
using test::RunResult;

TEST(Cli, DeformsABundledFish) {
  const std::string out = test::temp_path("bent.ply");
  const RunResult r = run_cli("deform --in " + fish("blub/fish_low_resolution.obj") + " --out '" +
                              out + "' --m 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const Mesh rest = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const Mesh bent = load_mesh(out);
  ASSERT_EQ(bent.vertex_count(), rest.vertex_count());
  EXPECT_EQ(bent.indices, rest.indices);
  double moved = 0.0;
  for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
    moved = std::max(moved, double(glm::length(bent.positions[v] - rest.positions[v])));
  }
  EXPECT_GT(moved, 0.05);  // the fish really bent
}

TEST(Cli, MatchesTheReferenceInTheIdentityFrame) {
  const Mesh rest = test::synthetic_fish(32, 24);
  const std::string in = test::temp_path("synthetic.obj");
  save_mesh(in, rest);
  const Mesh loaded = load_mesh(in);
  for (const char* mode : {"paper", "exact"}) {
    for (const char* normals : {"rotate", "jacobian"}) {
      const std::string out = test::temp_path("bent.obj");
      const RunResult r = run_cli("deform --in '" + in + "' --out '" + out + "' --m -0.75 --mode " +
                                  mode + " --normals " + normals + " --frame identity");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const Mesh bent = load_mesh(out);
      const RiggedMesh model =
          RiggedMesh::single_bend(loaded, BodyFrame::identity(), parse_bend_mode(mode));
      RigParameters m(model, 1);
      m.set(0, "m", -0.75f);
      const Mesh expected =
          instance_mesh(loaded, run_reference(model, m, parse_normal_mode(normals)), 0);
      for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
        EXPECT_LT(glm::length(bent.positions[v] - expected.positions[v]), 1e-5f) << mode << normals;
        EXPECT_LT(glm::length(bent.normals[v] - expected.normals[v]), 1e-4f) << mode << normals;
      }
    }
  }
}

TEST(Cli, WritesGltfWithTangents) {
  const std::string out = test::temp_path("bent.glb");
  const RunResult r = run_cli("deform --in " + fish("barramundi/BarramundiFish.gltf") + " --out '" +
                              out + "' --m 0.4 --mode exact --normals jacobian");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh bent = load_mesh(out);
  EXPECT_EQ(bent.vertex_count(), 2188u);
  EXPECT_TRUE(bent.has_tangents());
}

TEST(Cli, CheckPassesOnTheDefaultDevice) {
  const RunResult r = run_cli("check --in " + fish("blub/fish_low_resolution.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("bend exact     jacobian"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("OUT OF TOLERANCE"), std::string::npos) << r.out;
  const RunResult rig = run_cli("check --in " + fish("blub/fish_low_resolution.obj") + " --rig " +
                                fish("rigs/blub_low_resolution.rig.json"));
  ASSERT_EQ(rig.exit_code, 0) << rig.err << rig.out;
  EXPECT_NE(rig.out.find("rig            jacobian"), std::string::npos) << rig.out;
  const RunResult levels =
      run_cli("check --in " + fish("blub/fish_low_resolution.obj") + " --rig " +
              fish("rigs/blub_low_resolution.rig.json") + " --levels 2");
  ASSERT_EQ(levels.exit_code, 0) << levels.err << levels.out;
  EXPECT_NE(levels.out.find("rig level 1    jacobian"), std::string::npos) << levels.out;
  EXPECT_EQ(levels.out.find("OUT OF TOLERANCE"), std::string::npos) << levels.out;
  const RunResult no_rig =
      run_cli("check --in " + fish("blub/fish_low_resolution.obj") + " --levels 2");
  EXPECT_EQ(no_rig.exit_code, 2);
  EXPECT_NE(no_rig.err.find("--levels"), std::string::npos) << no_rig.err;
  const RunResult missing = run_cli("check --in '/nonexistent.obj'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(line_count(missing.err), 1);
}

TEST(Cli, BenchPrintsOneJsonObject) {
  for (const std::string& extra : std::vector<std::string>{
           "", " --rig " + fish("rigs/blub_low_resolution.rig.json") + " --path passes"}) {
    const RunResult r = run_cli("bench --mesh " + fish("blub/fish_low_resolution.obj") +
                                " --instances 8 --frames 3 --json" + extra);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 1) << r.out;
    for (const char* key :
         {"\"device\"", "\"vertices\":945", "\"instances\":8", "\"frames\":3",
          "\"seconds_per_frame_median\"", "\"vertices_per_second\"", "\"output_bytes_per_second\"",
          "\"write_bandwidth_bytes_per_second\""}) {
      EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
    }
  }
  EXPECT_EQ(
      run_cli("bench --mesh " + fish("blub/fish_low_resolution.obj") + " --instances 0").exit_code,
      2);
}

// bench --swim: a tank of the low-resolution Blub; the tank's steps recorded before the
// timed frames (the default) or taken inside the frame loop (live), both reported.
TEST(Cli, BenchSwimsWithRecordedOrLiveInputs) {
  const std::string swim = "bench --mesh " + fish("blub/fish_low_resolution.obj") + " --rig " +
                           fish("rigs/blub_low_resolution_swim.rig.json") +
                           " --swim --instances 12 --frames 3 --json";
  for (const std::string inputs : {"", "recorded", "live"}) {
    SCOPED_TRACE(inputs);
    const RunResult r = run_cli(swim + (inputs.empty() ? "" : " --swim-inputs " + inputs));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(line_count(r.out), 1) << r.out;
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
    EXPECT_EQ(j.at("swim_inputs").get<std::string>(), inputs.empty() ? "recorded" : inputs);
    EXPECT_EQ(j.at("instances").get<std::size_t>(), 12u);
    EXPECT_EQ(j.at("deformation").get<std::string>().rfind("swim ", 0), 0u);
    EXPECT_GT(j.at("seconds_per_frame_median").get<double>(), 0.0);
    EXPECT_GT(j.at("host_driver_seconds_median").get<double>(), 0.0);
    // The driver, then the deformation's kernels.
    EXPECT_GE(j.at("kernel_seconds_median").size(), 2u);
  }
  const RunResult bad = run_cli(swim + " --swim-inputs replayed");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(line_count(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("--swim-inputs 'replayed' is not recorded or live"), std::string::npos)
      << bad.err;
  EXPECT_TRUE(bad.out.empty()) << bad.out;
  const RunResult without_swim =
      run_cli("bench --mesh " + fish("blub/fish_low_resolution.obj") + " --swim-inputs live");
  EXPECT_EQ(without_swim.exit_code, 2);
  EXPECT_EQ(line_count(without_swim.err), 1) << without_swim.err;
  EXPECT_NE(without_swim.err.find("--swim-inputs 'live' needs --swim"), std::string::npos)
      << without_swim.err;
}

// bench --farm: the hall with levels beside the same hall at full detail, and its bad
// options named.
TEST(Cli, BenchFarmComparesLevelsWithFullDetail) {
  const std::string farm = "bench --mesh " + fish("blub/fish_low_resolution.obj") + " --rig " +
                           fish("rigs/blub_low_resolution_swim.rig.json") +
                           " --farm --instances 64 --tanks 4 --frames 2 --levels 3 --json";
  const RunResult r = run_cli(farm);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(line_count(r.out), 1) << r.out;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
  EXPECT_EQ(j.at("fish").get<std::size_t>(), 64u);
  EXPECT_EQ(j.at("tanks").get<std::size_t>(), 4u);
  EXPECT_TRUE(j.at("wall_occlusion").get<bool>());
  // 3 levels of the mesh and the coarsest again with its fins frozen.
  ASSERT_EQ(j.at("levels").size(), 4u);
  EXPECT_FALSE(j.at("levels")[2].at("fins_frozen").get<bool>());
  EXPECT_TRUE(j.at("levels")[3].at("fins_frozen").get<bool>());
  EXPECT_EQ(j.at("levels")[3].at("vertices"), j.at("levels")[2].at("vertices"));
  std::size_t drawn = 0, fewer = 0;
  for (const auto& level : j.at("levels")) drawn += level.at("fish").get<std::size_t>();
  EXPECT_EQ(drawn, j.at("fish_drawn").get<std::size_t>());
  EXPECT_GT(drawn, 0u);
  EXPECT_LE(drawn, 64u);
  fewer = j.at("with_levels").at("vertices_per_frame").get<std::size_t>();
  EXPECT_LT(fewer, j.at("full_detail").at("vertices_per_frame").get<std::size_t>());
  EXPECT_EQ(j.at("full_detail").at("vertices_per_frame").get<std::size_t>(), 64u * 945u);
  EXPECT_GT(j.at("with_levels").at("level_choice_seconds_median").get<double>(), 0.0);
  const std::string base = "bench --mesh " + fish("blub/fish_low_resolution.obj") + " --farm";
  const std::string rig = " --rig " + fish("rigs/blub_low_resolution_swim.rig.json");
  for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
           {base, "--farm needs --rig"},
           {base + rig + " --swim", "--farm"},
           {base + rig + " --tanks 0", "--tanks"},
           {base + rig + " --tanks 8 --instances 4", "--instances"},
           {base + rig + " --levels 0", "--levels"},
           {base + rig + " --pixel-budget -1", "--pixel-budget"}}) {
    SCOPED_TRACE(arguments);
    const RunResult bad = run_cli(arguments);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(line_count(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find(expected), std::string::npos) << bad.err;
    EXPECT_TRUE(bad.out.empty()) << bad.out;
  }
}

// Every key of `finflex bench --json` with its value: the counts as given, the passes
// and bytes the library says for the model, and the rates consistent with the times
// (docs/benchmarks.md's counters).
void expect_bench_json(const std::string& arguments, const RiggedMesh& model, RigPath path,
                       const std::string& deformation, NormalFormat format) {
  SCOPED_TRACE(arguments);
  const std::string mesh = test::data_path("blub/fish_low_resolution.obj");
  const RunResult r =
      run_cli("bench --mesh '" + mesh + "' --instances 8 --frames 3 --json" + arguments);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(line_count(r.out), 1) << r.out;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  const std::vector<std::string> expected_keys = {"device",
                                                  "mesh",
                                                  "deformation",
                                                  "normals",
                                                  "normal_format",
                                                  "layout",
                                                  "order",
                                                  "previous_positions",
                                                  "vertices",
                                                  "instances",
                                                  "frames",
                                                  "passes",
                                                  "seconds_per_frame_median",
                                                  "seconds_per_frame_min",
                                                  "vertices_per_second",
                                                  "output_bytes_per_second",
                                                  "moved_bytes_per_vertex",
                                                  "write_bandwidth_bytes_per_second",
                                                  "write_fraction",
                                                  "write_fraction_interleaved",
                                                  "host_enqueue_seconds_median",
                                                  "host_outputs",
                                                  "kernel_seconds_median",
                                                  "instances_per_item",
                                                  "lanes",
                                                  "streaming_stores",
                                                  "frames_ahead",
                                                  "huge_pages"};
  EXPECT_EQ(keys, expected_keys);  // in this order, none missing, none extra

  ClDeformer deformer(test::shared_context(), model);
  const bool passes = path == RigPath::kPasses;
  EXPECT_EQ(j.at("device").get<std::string>(), test::shared_context().description().device_name);
  // Frames run ahead of the device on GPUs only (bench::time_frames).
  EXPECT_EQ(j.at("frames_ahead").get<bool>(), test::shared_context().description().is_gpu());
  EXPECT_EQ(j.at("mesh").get<std::string>(), mesh);
  EXPECT_EQ(j.at("deformation").get<std::string>(), deformation);
  EXPECT_EQ(j.at("normals").get<std::string>(), "rotate");
  EXPECT_EQ(j.at("normal_format").get<std::string>(), to_string(format));
  EXPECT_EQ(j.at("vertices").get<std::size_t>(), 945u);
  EXPECT_EQ(j.at("instances").get<std::size_t>(), 8u);
  EXPECT_EQ(j.at("frames").get<std::size_t>(), 3u);
  EXPECT_EQ(j.at("passes").get<std::size_t>(), passes ? internal::pass_count(deformer) : 1u);
  if (passes) {
    EXPECT_EQ(j.at("passes").get<std::size_t>(), 2u);  // the hinges, then the body's bend
  }

  const double median = j.at("seconds_per_frame_median").get<double>();
  const double fastest = j.at("seconds_per_frame_min").get<double>();
  EXPECT_GT(fastest, 0.0);
  EXPECT_LE(fastest, median);
  const std::size_t plane_stride = deformer.layout(8, format).positions.plane_stride;
  const double bytes_per_vertex = format == NormalFormat::kHalf ? 18.0 : 24.0;
  EXPECT_DOUBLE_EQ(j.at("vertices_per_second").get<double>(), 945.0 * 8.0 / median);
  const double written = double(plane_stride) * 8.0 * bytes_per_vertex;
  EXPECT_DOUBLE_EQ(j.at("output_bytes_per_second").get<double>(), written / median);
  // Multi-pass: 12 bytes per attribute (positions, normals) each way per scratch record.
  EXPECT_DOUBLE_EQ(
      j.at("moved_bytes_per_vertex").get<double>(),
      bytes_per_vertex + (passes ? 24.0 * internal::scratch_records_per_slot(deformer) : 0.0));
  if (passes) {
    EXPECT_GT(internal::scratch_records_per_slot(deformer), 0.0);
  }
  const double write_bandwidth = j.at("write_bandwidth_bytes_per_second").get<double>();
  EXPECT_GT(write_bandwidth, 0.0);
  // write_fraction = write-only time / frame time = output rate / write-only rate.
  EXPECT_NEAR(j.at("write_fraction").get<double>(),
              j.at("output_bytes_per_second").get<double>() / write_bandwidth,
              1e-12 * j.at("write_fraction").get<double>());
  // On CPUs (frames waited for) the write-only kernel also runs after every frame: the
  // median of the frames' own ratios; none on GPUs (frames run ahead).
  if (test::shared_context().description().is_gpu()) {
    EXPECT_TRUE(j.at("write_fraction_interleaved").is_null());
  } else {
    EXPECT_GT(j.at("write_fraction_interleaved").get<double>(), 0.0);
  }
  EXPECT_GT(j.at("host_enqueue_seconds_median").get<double>(), 0.0);
  // A frame's kernels, in launch order: one per pass, or the fused kernels (one per
  // launch of the dispatch).
  const std::vector<double> kernels = j.at("kernel_seconds_median").get<std::vector<double>>();
  if (passes) {
    EXPECT_EQ(kernels.size(), internal::pass_count(deformer));
  } else {
    EXPECT_GE(kernels.size(), 1u);
  }
  for (double seconds : kernels) EXPECT_GT(seconds, 0.0);
  EXPECT_EQ(j.at("instances_per_item").get<std::size_t>(),
            internal::instances_per_item(deformer, deformer.layout(1, format)));
  EXPECT_EQ(j.at("lanes").get<std::size_t>(),
            internal::lanes(deformer, deformer.layout(1, format)));
  EXPECT_EQ(j.at("streaming_stores").get<bool>(),
            internal::streams_outputs(deformer, deformer.allocate(8, format)));
  // The system's transparent huge page mode, as the kernel says it.
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  const std::string transparent = j.at("huge_pages").at("transparent").get<std::string>();
  if (std::getline(thp, modes)) {
    EXPECT_NE(modes.find("[" + transparent + "]"), std::string::npos) << modes;
  } else {
    EXPECT_EQ(transparent, "unknown");
  }
  // The process's huge-page memory: a count of bytes (none with huge pages off), or null
  // where the system does not say.
  const auto& held = j.at("huge_pages").at("process_bytes");
  std::ifstream rollup("/proc/self/smaps_rollup");
  if (rollup) {
    ASSERT_TRUE(held.is_number_unsigned()) << held.dump();
    if (transparent == "never") {
      EXPECT_EQ(held.get<std::uint64_t>(), 0u);
    }
  } else {
    EXPECT_TRUE(held.is_null());
  }
}

// bench reports glibc's malloc huge-page tunable as the environment gives it: the last
// glibc.malloc.hugetlb among GLIBC_TUNABLES's settings, "0" when none.
TEST(Cli, BenchReportsGlibcHugePageTunable) {
  const std::string bench =
      "bench --mesh " + fish("blub/fish_low_resolution.obj") + " --instances 2 --frames 1 --json";
  for (const auto& [environment, expected] : std::vector<std::pair<std::string, std::string>>{
           {"env -u GLIBC_TUNABLES", "0"},
           {"GLIBC_TUNABLES=glibc.malloc.hugetlb=1", "1"},
           {"GLIBC_TUNABLES=glibc.malloc.hugetlb=0:glibc.malloc.arena_max=4:glibc.malloc.hugetlb=1",
            "1"},
           {"GLIBC_TUNABLES=glibc.malloc.arena_max=4", "0"}}) {
    const RunResult r = run_cli(bench, environment);
    ASSERT_EQ(r.exit_code, 0) << environment << ": " << r.err;
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
    EXPECT_EQ(j.at("huge_pages").at("glibc_malloc_hugetlb").get<std::string>(), expected)
        << environment;
  }
}

TEST(Cli, BenchJsonKeysAndValues) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  expect_bench_json(" --normal-format half", bend, RigPath::kFused, "bend paper",
                    NormalFormat::kHalf);
  const RiggedMesh rig(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), mesh));
  expect_bench_json(" --rig " + fish("rigs/blub_low_resolution.rig.json") + " --path passes", rig,
                    RigPath::kPasses, "rig passes", NormalFormat::kFloat32);
  const RunResult zero =
      run_cli("bench --mesh " + fish("blub/fish_low_resolution.obj") + " --instances 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_EQ(line_count(zero.err), 1) << zero.err;
  EXPECT_NE(zero.err.find("--instances"), std::string::npos) << zero.err;
}

// bench --layout/--order/--previous/--host: the layout is echoed, the bytes written per
// vertex follow its formats (float32x3 position, octahedral normal and tangent, float32x3
// previous position), the host map is timed; unknown names are refused by name.
TEST(Cli, BenchMeasuresOutputLayouts) {
  const std::string mesh = fish("blub/fish_low_resolution.obj");
  const RunResult r = run_cli("bench --mesh " + mesh +
                              " --instances 8 --frames 3 --json --layout compact --order mesh"
                              " --previous --host");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
  EXPECT_EQ(j.at("layout"), "compact");
  EXPECT_EQ(j.at("order"), "mesh");
  EXPECT_EQ(j.at("previous_positions"), true);
  EXPECT_EQ(j.at("host_outputs"), true);
  const bool tangents = load_mesh(test::data_path("blub/fish_low_resolution.obj")).has_tangents();
  EXPECT_EQ(j.at("moved_bytes_per_vertex").get<double>(),
            12.0 + 4.0 + (tangents ? 4.0 : 0.0) + 12.0);
  EXPECT_GT(j.at("host_map_seconds_median").get<double>(), 0.0);
  for (const auto& [option, value] :
       {std::pair<std::string, std::string>{"--layout", "soa"}, {"--order", "random"}}) {
    const RunResult bad = run_cli("bench --mesh " + mesh + " " + option + " " + value);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(line_count(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find(option + " '" + value + "'"), std::string::npos) << bad.err;
  }
}

// Lanes for every layout on CPUs: FinFlex's planes (with previous positions too), a
// vertex struct in one buffer (compact: float32x3 positions, octahedral normals) and
// attributes in arrays of their own as vectors, which stream; others lane by lane (the
// rig in mesh order), which do not.
struct BenchLanesCase {
  std::string options;
  bool streams;
};

void expect_bench_lanes_apply(const std::vector<BenchLanesCase>& cases) {
  const std::string mesh = fish("blub/fish_low_resolution.obj");
  for (const BenchLanesCase& c : cases) {
    SCOPED_TRACE(c.options);
    const RunResult r =
        run_cli("bench --mesh " + mesh +
                " --instances 8 --frames 2 --json --lanes 16 --stores streaming" + c.options);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("lanes").get<std::size_t>(), 16u);
    EXPECT_EQ(j.at("streaming_stores").get<bool>(), c.streams);
  }
}

TEST(Cli, BenchLanesApplyToEveryLayoutStreamingToPlanesAndStructs) {
  expect_bench_lanes_apply({{" --layout planes", true}, {" --layout arrays", true}});
}

// The same for the compact layout and a rig's layouts: a large test
// (tests/CMakeLists.txt).
TEST(CliLarge, BenchLanesApplyToTheCompactLayoutAndARigsLayouts) {
  const std::string rig = " --rig " + fish("rigs/blub_low_resolution.rig.json");
  expect_bench_lanes_apply({{" --layout compact", true},
                            {rig + " --layout arrays --host", true},
                            {rig + " --previous", true},
                            {rig + " --order mesh", false}});
}

TEST(Cli, InfoListsTheDefaultDevice) {
  const RunResult r = run_cli("info");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" * "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("      graphics interop: "), std::string::npos) << r.out;
}

struct BadCase {
  std::string arguments;  // after "deform --out OUT"
  std::string expected;   // substrings the one-line message must contain
  std::string also;
};

// Each case exits 2 with one line on stderr naming the problem, and writes nothing.
void expect_deform_fails(const std::vector<BadCase>& cases) {
  for (const BadCase& c : cases) {
    ASSERT_FALSE(c.expected.empty() || c.also.empty()) << c.arguments << ": say what to expect";
    const std::string out = test::temp_path("never.obj");
    const RunResult r = run_cli("deform --out '" + out + "' " + c.arguments);
    SCOPED_TRACE(c.arguments);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.also), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(Cli, BadInputsExitTwoWithOneLineAndWriteNothing) {
  const std::string in = fish("blub/fish_low_resolution.obj");
  const std::vector<BadCase> cases = {
      {"--in " + in + " --m 7", "--m", "out of range"},
      {"--in " + in + " --m -7", "--m", "out of range"},
      {"--in " + in + " --m nan", "--m", "NaN"},
      {"--in " + in + " --m inf", "--m", "infinite"},
      {"--in " + in + " --m abc", "--m", "not a number"},
      {"--in " + in + " --m 0.1 --mode spline", "--mode", "spline"},
      {"--in " + in + " --m 0.1 --normals smooth", "--normals", "smooth"},
      {"--in " + in + " --m 0.1 --frame body", "--frame", "body"},
      {"--in " + in + " --m 0.1 --device no-such-device", "device", "no-such-device"},
      {"--in '/nonexistent/fish.obj' --m 0.1", "/nonexistent/fish.obj",
       "No such file or directory"},
      {"--in " + fish("blub/README.md") + " --m 0.1", "README.md", "unsupported extension '.md'"},
      {"--in " + in + " --m 0.1 --head 1,2", "--head", "X,Y,Z"},
      {"--in " + in + " --m 0.1 --pivot 0,0,nan", "--pivot", "not finite"},
      {"--in " + in + " --m 0.1 --dorsal 0,0,0", "--dorsal", "non-zero direction"},
      {"--in " + in + " --m 0.1 --head 0,0,1 --frame identity", "--frame", "--head"},
      {"--m 0.1", "--in", "required"},
      {"--in " + in, "--m", "required"},
  };
  expect_deform_fails(cases);
}

TEST(Cli, AnExistingOutputIsLeftUntouchedOnError) {
  const std::string out = test::temp_path("existing.obj");
  { std::ofstream(out) << "previous content\n"; }
  const RunResult r = run_cli("deform --in " + fish("blub/fish_low_resolution.obj") + " --out '" +
                              out + "' --m 100");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(read_text(out), "previous content\n");
}

TEST(Cli, UnsupportedOutputFormatIsRejected) {
  const std::string out = test::temp_path("bent.xyz");
  const RunResult r = run_cli("deform --in " + fish("blub/fish_low_resolution.obj") + " --out '" +
                              out + "' --m 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".xyz"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, FrameOverridesChangeTheFrame) {
  // Blub's head is at mesh +z; saying it is at -z bends the other end about a new pivot.
  const std::string in = fish("blub/fish_low_resolution.obj");
  const std::string found = test::temp_path("found.obj"), flipped = test::temp_path("flipped.obj");
  ASSERT_EQ(run_cli("deform --in " + in + " --out '" + found + "' --m 0.5").exit_code, 0);
  const RunResult r =
      run_cli("deform --in " + in + " --out '" + flipped + "' --m 0.5 --head 0,0,-1 --pivot 0,0,1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh a = load_mesh(found), b = load_mesh(flipped);
  double difference = 0.0;
  for (std::size_t v = 0; v < a.vertex_count(); ++v) {
    difference = std::max(difference, double(glm::length(a.positions[v] - b.positions[v])));
  }
  EXPECT_GT(difference, 0.1);
}

TEST(Cli, DeformsWithARigOnBothPaths) {
  const std::string in = fish("blub/fish_low_resolution.obj");
  const std::string rig = fish("rigs/blub_low_resolution.rig.json");
  const Mesh rest = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  Mesh bent[2];
  int k = 0;
  for (const char* path : {"fused", "passes"}) {
    const std::string out = test::temp_path(std::string("rigged_") + path + ".ply");
    const RunResult r = run_cli("deform --in " + in + " --rig " + rig +
                                " --set body_m=0.4 --set tail_angle=-0.5 --out '" + out +
                                "' --path " + path + " --normals jacobian");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(std::string(path) + " path"), std::string::npos) << r.out;
    bent[k] = load_mesh(out);
    ASSERT_EQ(bent[k].vertex_count(), rest.vertex_count());  // the file keeps the input's order
    EXPECT_EQ(bent[k].indices, rest.indices);
    ++k;
  }
  double between = 0.0, moved = 0.0;
  for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
    between = std::max(between, double(glm::length(bent[0].positions[v] - bent[1].positions[v])));
    moved = std::max(moved, double(glm::length(bent[0].positions[v] - rest.positions[v])));
  }
  EXPECT_LT(between, 1e-5);
  EXPECT_GT(moved, 0.05);

  // The oracle: the library's reference for the same values (body_m 0.4, tail_angle
  // -0.5, the fins at rest), within the bounds of finflex/accuracy.hpp for two
  // stages. Values given to the wrong parameters would be off by far more.
  const RiggedMesh model(
      rest, resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), rest));
  RigParameters values(model, 1);
  values.set(0, "body_m", 0.4f);
  values.set(0, "tail_angle", -0.5f);
  const Mesh expected = instance_mesh(rest, run_reference(model, values, NormalMode::kJacobian), 0);
  const BodyFrame& root = model.rig().components.front().frame;
  const double stages = double(model.longest_path());
  for (const Mesh& got : bent) {
    for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
      ASSERT_LT(glm::length(glm::dvec3(got.positions[v]) - glm::dvec3(expected.positions[v])),
                stages * 4e-6 * (glm::length(root.origin) + root.length))
          << "vertex " << v;
      ASSERT_LT(glm::length(glm::dvec3(got.normals[v]) - glm::dvec3(expected.normals[v])),
                stages * 2e-5)
          << "vertex " << v;
    }
  }
}

// Each --set goes to the parameter it names: swapping the values between two
// parameters (or leaving one out) gives another fish.
TEST(Cli, RigParametersGoWhereTheirNamesSay) {
  const std::string in = fish("blub/fish_low_resolution.obj");
  const std::string rig = fish("rigs/blub_low_resolution.rig.json");
  const Mesh rest = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model(
      rest, resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), rest));
  const std::pair<const char*, float> settings[] = {{"body_m", -0.3f},
                                                    {"tail_angle", 0.7f},
                                                    {"right_pectoral_angle", 0.9f},
                                                    {"left_pectoral_angle", -1.1f}};
  std::string arguments;
  RigParameters values(model, 1);
  for (const auto& [name, value] : settings) {
    std::ostringstream text;
    text << " --set " << name << "=" << value;
    arguments += text.str();
    values.set(0, name, value);
  }
  const std::string out = test::temp_path("rigged.ply");  // binary: floats as written
  const RunResult r =
      run_cli("deform --in " + in + " --rig " + rig + arguments + " --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& [name, value] : settings) {
    std::ostringstream said;
    said << name << " = " << value;
    EXPECT_NE(r.out.find(said.str()), std::string::npos) << said.str() << " in " << r.out;
  }
  const Mesh got = load_mesh(out);
  // The same values on this process's device (the same kernel, the same floats: the
  // binary PLY keeps them exactly), and the reference within two stages' bounds.
  ClDeformer deformer(test::shared_context(), model);
  const Mesh on_device =
      instance_mesh(rest, test::run_on_device(deformer, values, NormalMode::kRotate), 0);
  const Mesh reference = instance_mesh(rest, run_reference(model, values, NormalMode::kRotate), 0);
  const BodyFrame& root = model.rig().components.front().frame;
  const double bound = 2.0 * 4e-6 * (glm::length(root.origin) + root.length);
  for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
    ASSERT_EQ(got.positions[v], on_device.positions[v]) << "vertex " << v;
    // Normals are renormalised when a file is read: rotate-mode normals are unit
    // within 2e-6 (Geometry.RotatedNormalsStayUnit), so they move by as much.
    ASSERT_LT(glm::length(got.normals[v] - on_device.normals[v]), 2e-6f) << "vertex " << v;
    ASSERT_LT(glm::length(glm::dvec3(got.positions[v]) - glm::dvec3(reference.positions[v])), bound)
        << "vertex " << v;
  }
}

TEST(Cli, BadRigInputsExitTwoAndWriteNothing) {
  const std::string in = fish("blub/fish_low_resolution.obj");
  const std::string rig = fish("rigs/blub_low_resolution.rig.json");
  const std::string broken = test::temp_path("broken.rig.json");
  { std::ofstream(broken) << "{\"components\": [ {\"name\": \"body\", \"select\": \"all\",}"; }
  // Two siblings taking the same vertices: resolves only against the mesh.
  const std::string overlapping = test::temp_path("overlapping.rig.json");
  {
    std::ofstream(overlapping) << R"({"components": [
             {"name": "body", "select": "all", "chain": []},
             {"name": "tail", "parent": "body", "select": {"box": {"min": [-9, -9, -9], "max": [-0.2, 9, 9]}},
              "chain": [{"deformer": "hinge", "param": "a"}]},
             {"name": "fin", "parent": "body", "select": {"box": {"min": [-9, -9, -9], "max": [-0.3, 9, 9]}},
              "chain": [{"deformer": "hinge", "param": "b"}]}]})";
  }
  const std::vector<BadCase> cases = {
      {"--in " + in + " --rig " + rig + " --set no_such=1", "--set", "no_such"},
      {"--in " + in + " --rig " + rig + " --set body_m", "--set", "NAME=VALUE"},
      {"--in " + in + " --rig " + rig + " --set body_m=abc", "body_m", "not a number"},
      {"--in " + in + " --rig " + rig + " --set body_m=50", "body_m[0]", "out of range"},
      {"--in " + in + " --rig " + rig + " --set tail_angle=nan", "tail_angle[0]", "NaN"},
      {"--in " + in + " --rig " + rig + " --path sideways", "--path", "sideways"},
      {"--in " + in + " --rig " + rig + " --m 0.3", "--m", "--rig"},
      {"--in " + in + " --rig '/nonexistent.rig.json'", "--rig", "nonexistent"},
      {"--in " + in + " --rig '" + broken + "'", "--rig", "malformed JSON"},
      {"--in " + in + " --rig '" + overlapping + "'", "'fin'", "'tail'"},
      {"--in " + in + " --m 0.1 --set body_m=1", "--set", "--rig"},
  };
  expect_deform_fails(cases);
}

TEST(Cli, ClampBringsParameterIntoRange) {
  const std::string out = test::temp_path("clamped.obj");
  const RunResult r = run_cli("deform --in " + fish("blub/fish_low_resolution.obj") + " --out '" +
                              out + "' --m 100 --clamp");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out));
}

// The tank with the low-resolution Blub (fast), a few fish, a fraction of a second.
std::string small_swim(const std::string& fish_count = "12") {
  return "swim --fish " + fish_count + " --seconds 0.2 --fps 30 --species " +
         fish("blub/fish_low_resolution.obj") + ":" +
         test::data_path("rigs/blub_low_resolution_swim.rig.json");
}

TEST(Cli, SwimsAndWritesASummaryAndMeshes) {
  const std::string out = test::temp_path("tank");
  // --no-render: the summary and the meshes (the pictures: test_cli_pictures.cpp).
  const RunResult r =
      run_cli(small_swim() + " --out '" + out + "' --mesh-frames 0,last --seed 4 --no-render");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("swam 12 fish (12 blub_low_resolution)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("6 frames"), std::string::npos) << r.out;
  const std::string summary = read_text(out + "/summary.json");
  for (const char* key : {"\"fish\": 12", "\"frames\": 6", "\"seed\": 4", "\"tracks\"",
                          "\"vertices_per_frame\": 11340"}) {
    EXPECT_NE(summary.find(key), std::string::npos) << key;
  }
  // Both frames as whole-tank meshes: 12 fish of 945 vertices, in the tank's water.
  for (const char* frame : {"tank_frame_000000.glb", "tank_frame_000005.glb"}) {
    const Mesh tank = load_mesh(out + "/" + frame);
    EXPECT_EQ(tank.vertex_count(), 12u * 945u);
    for (const glm::vec3& p : tank.positions) {
      EXPECT_LT(std::hypot(p.x, p.z), 1.83f + 0.3f);
      EXPECT_GT(p.y, -0.2f);
      EXPECT_LT(p.y, 1.22f + 0.2f);
    }
  }
  // The same seed, the same tank.
  const std::string again = test::temp_path("tank_again");
  ASSERT_EQ(run_cli(small_swim() + " --out '" + again + "' --mesh-frames last --seed 4 --no-render")
                .exit_code,
            0);
  EXPECT_EQ(read_text(out + "/tank_frame_000005.glb"), read_text(again + "/tank_frame_000005.glb"));
}

TEST(Cli, BadSwimInputsExitTwoAndWriteNothing) {
  const std::string rig_without_body = test::data_path("rigs/blub_low_resolution.rig.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--fish 0", "--fish"},
      {"--fish -1", "--fish '-1'"},
      {"--fish 2.5", "--fish"},
      {" --fps 0", "--fps"},
      {" --seconds nan", "--seconds"},
      {" --tank 0.5,0.5", "tank.diameter"},
      {" --tank 3", "--tank"},
      {" --seed x", "--seed"},
      {" --normals smooth", "--normals"},
      {" --mesh-frames 99", "--mesh-frames '99'"},
      {" --levels 9", "--levels '9'"},
      {" --levels 2 --pixel-budget 0", "--pixel-budget"},
      {" --levels 2 --pixel-budget nan", "--pixel-budget"},
      {" --levels 2 --triangle-ratio 1", "--triangle-ratio"},
      {" --levels 2 --mesh-frames last", "not with --levels"},
      {" --levels 2 --annotate", "--annotate takes its keypoints"},
      {" --levels 2 --reference-draw", "--reference-draw draws"},
      {" --tanks 0", "--tanks '0'"},
      {" --tanks 1025", "--tanks"},
      {" --species '/nonexistent.obj:x.rig.json'", "/nonexistent.obj"},
      {" --species nocolon", "MESH:RIG"},
      {" --species " + fish("blub/fish_low_resolution.obj") + ":" + rig_without_body,
       "needs a body"},
      {" --device no-such-device", "no-such-device"},
  };
  for (const auto& [arguments, expected] : cases) {
    const std::string out = test::temp_path("never");
    // Cases starting with "--fish" give the count themselves; the species option is
    // repeatable, so a case's own --species comes after the small tank's one and
    // both are read: the bad one fails. Without the renderer, so that this program
    // keeps leak detection under AddressSanitizer (tests/sanitizers/README.md); the
    // cases that reach the renderer are in test_cli_pictures.
    const bool own_count = arguments.rfind("--fish", 0) == 0;
    const RunResult r =
        run_cli((own_count ? small_swim(arguments.substr(7)) : small_swim() + arguments) +
                " --no-render --out '" + out + "'");
    SCOPED_TRACE(arguments);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const RunResult no_out = run_cli(small_swim() + " --mesh-frames 1");
  EXPECT_EQ(no_out.exit_code, 2);
  EXPECT_NE(no_out.err.find("--mesh-frames needs --out"), std::string::npos) << no_out.err;
  // --out naming a file.
  const std::string file = test::temp_path("a_file");
  { std::ofstream(file) << "keep\n"; }
  const RunResult r = run_cli(small_swim() + " --out '" + file + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(file), "keep\n");
}

// --clamp writes what the limit itself gives: m = +-100 becomes +-limit (the library's
// RigParameter::limit, 0.5 / x_max), and so does a rig parameter.
TEST(Cli, ClampedOutputIsTheOutputAtTheLimit) {
  const std::string in = fish("blub/fish_low_resolution.obj");
  const Mesh rest = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const RiggedMesh model = RiggedMesh::single_bend(rest, find_body_frame(rest), BendMode::kPaper);
  const float limit = static_cast<float>(test::bend_limit(model));
  ClDeformer deformer(test::shared_context(), model);
  for (float sign : {1.0f, -1.0f}) {
    const std::string clamped = test::temp_path("clamped.ply");  // binary: floats as written
    const RunResult r = run_cli("deform --in " + in + " --out '" + clamped + "' --m " +
                                (sign > 0 ? "100" : "-100") + " --clamp");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // The value the library clamps to: the float next to the limit, towards 0.
    float used = 0.0f;
    check_parameters(model.rig(), test::values_of(model, {sign * 100.0f}).view(), true, &used);
    EXPECT_EQ(used, sign * std::nextafter(limit, 0.0f));
    std::ostringstream said;
    said << "m = " << used;
    EXPECT_NE(r.out.find(said.str()), std::string::npos) << said.str() << " in " << r.out;
    const Mesh got = load_mesh(clamped);
    // The library at the limit: on this process's device (the same kernel: the same
    // floats) and in the reference.
    const Mesh at_limit = instance_mesh(
        rest, test::run_on_device(deformer, test::values_of(model, {used}), NormalMode::kRotate),
        0);
    const Mesh reference = instance_mesh(
        rest, run_reference(model, test::values_of(model, {used}), NormalMode::kRotate), 0);
    const BodyFrame& frame = model.rig().components[0].frame;
    for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
      ASSERT_EQ(got.positions[v], at_limit.positions[v]) << "vertex " << v;
      ASSERT_LT(glm::length(got.normals[v] - at_limit.normals[v]), 2e-6f)
          << "vertex " << v;  // renormalised on reading, as above
      ASSERT_LT(glm::length(glm::dvec3(got.positions[v]) - glm::dvec3(reference.positions[v])),
                4e-6 * (glm::length(frame.origin) + frame.length))
          << "vertex " << v;
    }
  }
  // A rig parameter: body_m = 50 with --clamp is body_m at its limit.
  const RiggedMesh rigged(
      rest, resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution.rig.json")), rest));
  const std::string out = test::temp_path("rig_clamped.ply");
  const RunResult r =
      run_cli("deform --in " + in + " --rig " + fish("rigs/blub_low_resolution.rig.json") +
              " --set body_m=50 --set tail_angle=-9 --clamp --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  RigParameters beyond(rigged, 1);
  beyond.set(0, "body_m", 50.0f);
  beyond.set(0, "tail_angle", -9.0f);
  RigParameters at_limits(rigged, 1);
  check_parameters(rigged.rig(), beyond.view(), true, at_limits.values().data());
  const std::vector<RigParameter>& parameters = rigged.rig().parameters;
  EXPECT_EQ(at_limits.get(0, rigged.rig().param_index("body_m")),
            std::nextafter(static_cast<float>(parameters[0].limit), 0.0f));
  EXPECT_EQ(at_limits.get(0, rigged.rig().param_index("tail_angle")),
            -std::nextafter(3.14159265f, 0.0f));
  ClDeformer rig_deformer(test::shared_context(), rigged);
  const Mesh expected =
      instance_mesh(rest, test::run_on_device(rig_deformer, at_limits, NormalMode::kRotate), 0);
  const Mesh got = load_mesh(out);
  for (std::size_t v = 0; v < rest.vertex_count(); ++v) {
    ASSERT_EQ(got.positions[v], expected.positions[v]) << "vertex " << v;
    ASSERT_LT(glm::length(got.normals[v] - expected.normals[v]), 2e-6f)
        << "vertex " << v;  // renormalised on reading, as above
  }
}

// ----------------------------------------------------------------------------------
// subdivide and rig-info

TEST(Cli, SubdivideWritesWhatTheLibraryComputes) {
  const std::string in = test::data_path("blub/fish_control_mesh.obj");
  const std::string out = test::temp_path("dense.ply");
  const RunResult r = run_cli("subdivide --in '" + in + "' --levels 2 --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const Mesh expected = subdivide_loop(load_mesh(in), 2);
  const Mesh got = load_mesh(out);
  ASSERT_EQ(got.vertex_count(), expected.vertex_count());
  EXPECT_EQ(got.indices, expected.indices);
  for (std::size_t v = 0; v < got.vertex_count(); ++v) {
    ASSERT_EQ(got.positions[v], expected.positions[v]) << "vertex " << v;  // binary PLY
  }
  std::ostringstream said;
  said << expected.vertex_count() << " vertices, " << expected.triangle_count() << " triangles";
  EXPECT_NE(r.out.find(said.str()), std::string::npos) << r.out;
  // Each level splits every triangle in four.
  EXPECT_EQ(expected.triangle_count(), 16 * load_mesh(in).triangle_count());
}

TEST(Cli, SubdivideBadInputsExitTwoAndWriteNothing) {
  const std::string in = "'" + test::data_path("blub/fish_control_mesh.obj") + "'";
  const std::pair<std::string, std::pair<std::string, std::string>> cases[] = {
      {"--in " + in + " --levels 9", {"levels", "above the limit 8"}},
      {"--in " + in + " --levels -1", {"levels", "[0, 8]"}},
      {"--in '/nonexistent/cage.obj' --levels 1",
       {"/nonexistent/cage.obj", "No such file or directory"}},
  };
  for (const auto& [arguments, expected] : cases) {
    const std::string out = test::temp_path("never.obj");
    const RunResult r = run_cli("subdivide " + arguments + " --out '" + out + "'");
    SCOPED_TRACE(arguments);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected.first), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expected.second), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const std::string unsupported = test::temp_path("dense.xyz");
  const RunResult r = run_cli("subdivide --in " + in + " --levels 1 --out '" + unsupported + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".xyz"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(unsupported));
}

TEST(Cli, RigInfoPrintsTheRigAndLabelsEveryVertex) {
  const std::string mesh_path = test::data_path("blub/fish_low_resolution.obj");
  const std::string rig_path = test::data_path("rigs/blub_low_resolution.rig.json");
  const std::string labels = test::temp_path("labels.txt");
  const RunResult r = run_cli("rig-info --in '" + mesh_path + "' --rig '" + rig_path +
                              "' --labels '" + labels + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh mesh = load_mesh(mesh_path);
  const RiggedMesh model(mesh, resolve_rig(load_rig_file(rig_path), mesh));
  const Rig& rig = model.rig();
  EXPECT_NE(r.out.find("945 vertices): 4 components, 4 parameters"), std::string::npos) << r.out;
  for (const RigComponent& component : rig.components) {
    std::ostringstream own;
    own << component.name << " (parent "
        << (component.parent < 0 ? "none" : rig.components[component.parent].name) << ", depth "
        << (component.parent < 0 ? 0 : 1) << "): " << component.vertices.size() << " own vertices";
    EXPECT_NE(r.out.find(own.str()), std::string::npos) << own.str() << " in " << r.out;
  }
  for (const RigParameter& parameter : rig.parameters) {
    char range[128];
    std::snprintf(range, sizeof range, "parameter %s in [%.4f, %.4f]", parameter.name.c_str(),
                  -parameter.limit, parameter.limit);
    EXPECT_NE(r.out.find(range), std::string::npos) << range << " in " << r.out;
  }
  EXPECT_NE(r.out.find("parameter body_m in [-0.8547, 0.8547]"), std::string::npos) << r.out;
  // The levels of detail (4 by default), each as make_detail_levels makes it.
  const DetailLevels levels = make_detail_levels(model, LevelOptions{});
  for (std::size_t k = 0; k < levels.size(); ++k) {
    char row[128];
    std::snprintf(row, sizeof row, "  %5zu %9zu %10zu ", k, levels.level(k).vertex_count,
                  levels.level(k).triangle_count);
    EXPECT_NE(r.out.find(row), std::string::npos) << row << " in " << r.out;
  }

  // The labels: a comment line, then one line per mesh vertex, in order: its
  // component and its position in the root's body frame (6 decimals).
  std::ifstream file(labels);
  std::string line;
  ASSERT_TRUE(std::getline(file, line));
  EXPECT_EQ(line.rfind("# ", 0), 0u) << line;
  const BodyFrame& root = rig.components.front().frame;
  std::size_t v = 0;
  while (std::getline(file, line)) {
    ASSERT_LT(v, mesh.vertex_count()) << "more lines than vertices";
    std::istringstream fields(line);
    std::string name;
    glm::dvec3 p;
    ASSERT_TRUE(fields >> name >> p.x >> p.y >> p.z) << line;
    EXPECT_EQ(name, rig.components[model.component_of_vertex()[v]].name) << "vertex " << v;
    EXPECT_LT(glm::length(p - root.point_to_local(glm::dvec3(mesh.positions[v]))), 1e-6)
        << "vertex " << v;
    ++v;
  }
  EXPECT_EQ(v, mesh.vertex_count());

  const RunResult bad = run_cli("rig-info --in '" + mesh_path + "' --rig '" + rig_path +
                                "' --labels '" + test::temp_path("") + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(line_count(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("--labels"), std::string::npos) << bad.err;
  for (const std::string& flags :
       {std::string("--levels 0"), std::string("--levels 9"), std::string("--triangle-ratio 1"),
        std::string("--triangle-ratio nan")}) {
    const RunResult refused =
        run_cli("rig-info --in '" + mesh_path + "' --rig '" + rig_path + "' " + flags);
    EXPECT_EQ(refused.exit_code, 2) << flags;
    EXPECT_EQ(line_count(refused.err), 1) << refused.err;
    EXPECT_NE(refused.err.find(flags.substr(0, flags.find(' '))), std::string::npos) << refused.err;
  }
  const RunResult no_rig = run_cli("rig-info --in '" + mesh_path + "' --rig '/nonexistent.json'");
  EXPECT_EQ(no_rig.exit_code, 2);
  EXPECT_EQ(line_count(no_rig.err), 1) << no_rig.err;
  EXPECT_NE(no_rig.err.find("nonexistent.json"), std::string::npos) << no_rig.err;
}

}  // namespace
}  // namespace finflex

// The finflex command line as other tools call it: exit codes, the one-line error
// message naming the problem, and no output file on any error.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string read_text(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

RunResult run_cli(const std::string& arguments) {
  const std::string out_path = test::temp_path("stdout.txt");
  const std::string err_path = test::temp_path("stderr.txt");
  const std::string command = std::string("POCL_CACHE_DIR=") + FINFLEX_TEST_POCL_CACHE + " '" +
                              FINFLEX_CLI_PATH + "' " + arguments + " >'" + out_path + "' 2>'" +
                              err_path + "' </dev/null";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_text(out_path);
  result.err = read_text(err_path);
  return result;
}

std::string fish(const char* relative) { return "'" + test::data_path(relative) + "'"; }

int line_count(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

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

TEST(Cli, InfoListsTheDefaultDevice) {
  const RunResult r = run_cli("info");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" * "), std::string::npos) << r.out;
}

struct BadCase {
  std::string arguments;  // after "deform --out OUT"
  std::string expected;   // substrings the one-line message must contain
  std::string also;
};

// Each case exits 2 with one line on stderr naming the problem, and writes nothing.
void expect_deform_fails(const std::vector<BadCase>& cases) {
  for (const BadCase& c : cases) {
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
      {"--in '/nonexistent/fish.obj' --m 0.1", "/nonexistent/fish.obj", ""},
      {"--in " + fish("blub/README.md") + " --m 0.1", "README.md", ""},
      {"--in " + in + " --m 0.1 --head 1,2", "--head", "X,Y,Z"},
      {"--in " + in + " --m 0.1 --pivot 0,0,nan", "--pivot", "not finite"},
      {"--in " + in + " --m 0.1 --dorsal 0,0,0", "--dorsal", ""},
      {"--in " + in + " --m 0.1 --head 0,0,1 --frame identity", "--frame", "--head"},
      {"--m 0.1", "--in", ""},
      {"--in " + in, "--m", ""},
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
      {"--in " + in + " --rig '" + broken + "'", "--rig", ""},
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
  const RunResult r = run_cli(small_swim() + " --out '" + out + "' --mesh-frames 0,last --seed 4");
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
  ASSERT_EQ(run_cli(small_swim() + " --out '" + again + "' --mesh-frames last --seed 4").exit_code,
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
    // both are read: the bad one fails.
    const bool own_count = arguments.rfind("--fish", 0) == 0;
    const RunResult r =
        run_cli((own_count ? small_swim(arguments.substr(7)) : small_swim() + arguments) +
                " --out '" + out + "'");
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

}  // namespace
}  // namespace finflex

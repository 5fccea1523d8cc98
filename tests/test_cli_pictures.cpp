// The finflex tool's pictures: `swim --out` renders PNG frames, a video and the camera
// file; `swim --annotate` writes masks and COCO annotations that agree with the
// engine's own deformed vertices projected through that camera file, and that
// pycocotools loads; `bake` writes every format; every bad input exits 2 with one line
// and leaves nothing behind.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "finflex/finflex.hpp"
#include "landmarks.hpp"
#include "support/run_cli.hpp"
#include "support/test_support.hpp"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace finflex {
namespace {

namespace fs = std::filesystem;
using test::fish;
using test::line_count;
using test::read_text;
using test::run_cli;
using test::RunResult;

const char* kLowResolutionBlub = "blub/fish_low_resolution.obj";

std::string low_resolution_species() {
  return fish(kLowResolutionBlub) + ":" + test::data_path("rigs/blub_low_resolution_swim.rig.json");
}

// A few low-resolution Blubs for a fraction of a second.
std::string small_swim(const std::string& fish_count = "12") {
  return "swim --fish " + fish_count + " --seconds 0.1 --fps 30 --species " +
         low_resolution_species();
}

nlohmann::json read_json(const std::string& path) {
  nlohmann::json json;
  std::ifstream(path) >> json;
  return json;
}

std::size_t files_in(const std::string& folder) {
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(folder)) count += entry.is_regular_file();
  return count;
}

TEST(CliPictures, SwimWritesFramesAVideoAndTheCamera) {
  const std::string out = test::temp_path("tank");
  const RunResult r = run_cli(small_swim() + " --size 160x90 --video apng --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rendered 160x90"), std::string::npos) << r.out;
  EXPECT_EQ(files_in(out + "/frames"), 3u);  // 0.1 s at 30 fps
  for (int frame = 0; frame < 3; ++frame) {
    int width = 0, height = 0, channels = 0;
    unsigned char* pixels =
        stbi_load((out + "/frames/frame_00000" + std::to_string(frame) + ".png").c_str(), &width,
                  &height, &channels, 3);
    ASSERT_NE(pixels, nullptr);
    EXPECT_EQ(width, 160);
    EXPECT_EQ(height, 90);
    stbi_image_free(pixels);
  }
  // The APNG holds every frame (acTL's count).
  const std::string apng = read_text(out + "/swim.png");
  const std::size_t actl = apng.find("acTL");
  ASSERT_NE(actl, std::string::npos);
  EXPECT_EQ(static_cast<unsigned char>(apng[actl + 7]), 3u);
  const nlohmann::json camera = read_json(out + "/camera.json");
  EXPECT_EQ(camera["width"], 160);
  EXPECT_NEAR(camera["fy"].get<double>(), 45.0 / std::tan(20.0 * M_PI / 180.0), 1e-6);
  const nlohmann::json summary = read_json(out + "/summary.json");
  for (const char* share : {"deform", "hand_off", "draw", "read_back", "files"}) {
    EXPECT_GE(summary["rendering"]["share_of_frame"][share].get<double>(), 0.0) << share;
  }
  EXPECT_GT(summary["rendering"]["frames_per_second"].get<double>(), 0.0);
  // Drawn, the next frame's tank steps on a thread beside the draw: the last frame's
  // fish, the tracks and the corrections are those of a run that draws nothing.
  const std::string drawn = test::temp_path("tank_drawn"),
                    undrawn = test::temp_path("tank_undrawn");
  const std::string frames = " --mesh-frames last --out '";
  ASSERT_EQ(run_cli(small_swim() + " --size 160x90 --video none" + frames + drawn + "'").exit_code,
            0);
  ASSERT_EQ(run_cli(small_swim() + " --no-render" + frames + undrawn + "'").exit_code, 0);
  const std::string last = read_text(drawn + "/tank_frame_000002.glb");
  EXPECT_FALSE(last.empty());
  EXPECT_EQ(last, read_text(undrawn + "/tank_frame_000002.glb"));
  const nlohmann::json with = read_json(drawn + "/summary.json"),
                       without = read_json(undrawn + "/summary.json");
  EXPECT_EQ(with["tracks"], without["tracks"]);
  EXPECT_EQ(with["corrections"], without["corrections"]);
  EXPECT_EQ(with["brakes"], without["brakes"]);
  // The hand-off's path (beside PoCL: external memory where Mesa's lavapipe is
  // installed, else the copy), why each path before it could not run, and its time.
  const nlohmann::json& hand_off = summary["rendering"]["hand_off"];
  const std::string path = hand_off["path"].get<std::string>();
  EXPECT_TRUE(path == "external-memory" || path == "shared" || path == "copy") << path;
  EXPECT_EQ(hand_off.contains("why_not_external"), path != "external-memory");
  EXPECT_EQ(hand_off.contains("why_not_shared"), path == "copy");
  if (path == "external-memory") {
    EXPECT_TRUE(hand_off.contains("vulkan_device") && hand_off.contains("import"));
  }
  if (std::getenv("FINFLEX_EXPECT_EXTERNAL_MEMORY") != nullptr) {
    EXPECT_EQ(path, "external-memory");
  }
  EXPECT_GE(hand_off["seconds_per_frame_mean"].get<double>(), 0.0);
  EXPECT_NE(r.out.find("hand-off: " + path), std::string::npos) << r.out;
  // Nothing else is left next to the output folder (the staging folder is gone).
  std::size_t beside = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(out).parent_path())) {
    beside += entry.path().filename().string().find(".partial") != std::string::npos;
  }
  EXPECT_EQ(beside, 0u);
}

// With --draw written the frames that write nothing are not drawn: the frames a run
// writes are the same, byte for byte, as the same frames of a run that writes every frame (with
// varied optics and noise, which are drawn per frame, and the dataset).
TEST(CliPictures, DrawingOnlyTheWrittenFramesChangesNothingInThem) {
  const std::string every = test::temp_path("every_frame");
  const std::string some = test::temp_path("two_frames");
  const std::string swim = "swim --fish 12 --seconds 0.2 --fps 30 --species " +
                           low_resolution_species() +
                           " --size 160x90 --video none --annotate --vary-optics --noise 1,2";
  const RunResult all = run_cli(swim + " --out '" + every + "'");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const RunResult two = run_cli(swim + " --image-frames 3,5 --draw written --out '" + some + "'");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(files_in(some + "/frames"), 2u);
  for (const char* frame : {"frame_000003.png", "frame_000005.png"}) {
    EXPECT_EQ(read_text(some + "/frames/" + frame), read_text(every + "/frames/" + frame)) << frame;
    EXPECT_EQ(read_text(some + "/masks/" + std::string(frame)),
              read_text(every + "/masks/" + std::string(frame)))
        << frame;
  }
  // The two frames' annotations, ids aside.
  const auto by_file = [](const nlohmann::json& coco) {
    std::map<int, std::string> file_of;
    for (const nlohmann::json& image : coco["images"]) file_of[image["id"]] = image["file_name"];
    std::map<std::string, std::vector<nlohmann::json>> out;
    for (nlohmann::json annotation : coco["annotations"]) {
      const std::string file = file_of[annotation["image_id"]];
      annotation.erase("id");
      annotation.erase("image_id");
      out[file].push_back(annotation);
    }
    return out;
  };
  const auto got = by_file(read_json(some + "/coco.json"));
  const auto every_frame = by_file(read_json(every + "/coco.json"));
  std::map<std::string, std::vector<nlohmann::json>> wanted;
  for (const auto& [file, annotations] : every_frame) {
    if (file.find("000003") != std::string::npos || file.find("000005") != std::string::npos)
      wanted[file] = annotations;
  }
  EXPECT_EQ(got.size(), 2u);
  EXPECT_EQ(got, wanted);
  // The summary's frame times are the drawn frames' (after the first): 2 of 5.
  EXPECT_NE(two.out.find("a drawn frame (mean of 2)"), std::string::npos) << two.out;
  EXPECT_NE(all.out.find("a drawn frame (mean of 5)"), std::string::npos) << all.out;
}

std::vector<std::uint16_t> read_mask(const std::string& path, int& width, int& height) {
  int channels = 0;
  stbi_us* data = stbi_load_16(path.c_str(), &width, &height, &channels, 1);
  EXPECT_NE(data, nullptr) << path;
  if (data == nullptr) return {};
  std::vector<std::uint16_t> out(data, data + std::size_t(width) * std::size_t(height));
  stbi_image_free(data);
  return out;
}

struct Projection {
  glm::dvec2 low{1e9}, high{-1e9};
  bool in_front = true;
};

// The dataset's ground truth against the engine's own geometry: the frames written
// as whole-tank meshes (world space, the fish in tank order) projected through
// camera.json.
TEST(CliPictures, OnlyTheKeypointsAskedForAreAnnotated) {
  const std::string out = test::temp_path("two_keypoints");
  const RunResult r = run_cli(small_swim() +
                              " --annotate --keypoints tail_fork,snout --formats "
                              "coco,yolo --video none --out '" +
                              out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json coco = read_json(out + "/coco.json");
  EXPECT_EQ(coco["categories"][0]["keypoints"], nlohmann::json({"snout", "tail_fork"}));
  EXPECT_EQ(coco["categories"][0]["skeleton"], nlohmann::json({{1, 2}}));
  ASSERT_FALSE(coco["annotations"].empty());
  for (const nlohmann::json& a : coco["annotations"]) {
    EXPECT_EQ(a["keypoints"].size(), 6u);
    EXPECT_EQ(a["keypoints_camera_m"].size(), 2u);
  }
  const std::string yaml = read_text(out + "/yolo/pose/dataset.yaml");
  EXPECT_NE(yaml.find("kpt_shape: [2, 3]\nflip_idx: [0, 1]"), std::string::npos) << yaml;
}

TEST(CliPictures, MasksBoxesAndKeypointsAgreeWithTheProjectedVertices) {
  const std::string out = test::temp_path("dataset");
  const RunResult r = run_cli(small_swim("16") +
                              " --seed 7 --size 320x180 --camera above "
                              "--annotate --video none --mesh-frames 0,2 --out '" +
                              out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json camera = read_json(out + "/camera.json");
  const nlohmann::json coco = read_json(out + "/coco.json");
  glm::dmat4 camera_from_world(1.0);
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col)
      camera_from_world[col][row] = camera["camera_from_world"][row][col];
  }
  const double fx = camera["fx"], fy = camera["fy"], cx = camera["cx"], cy = camera["cy"];
  const auto project = [&](const glm::vec3& world) {
    const glm::dvec4 p = camera_from_world * glm::dvec4(glm::dvec3(world), 1.0);
    return glm::dvec3(fx * p.x / p.z + cx, fy * p.y / p.z + cy, p.z);
  };
  const Mesh rest = load_mesh(test::data_path(kLowResolutionBlub));
  const RiggedMesh model(
      rest,
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution_swim.rig.json")), rest));
  const pictures::FishLandmarks marks = pictures::find_landmarks(model);
  const std::size_t vertices = rest.vertex_count();

  for (int frame : {0, 2}) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const Mesh tank = load_mesh(out + "/tank_frame_00000" + std::to_string(frame) + ".glb");
    ASSERT_EQ(tank.vertex_count(), 16 * vertices);
    std::vector<Projection> fish(16);
    for (std::size_t i = 0; i < 16; ++i) {
      for (std::size_t v = 0; v < vertices; ++v) {
        const glm::dvec3 p = project(tank.positions[i * vertices + v]);
        fish[i].low = glm::min(fish[i].low, glm::dvec2(p));
        fish[i].high = glm::max(fish[i].high, glm::dvec2(p));
        fish[i].in_front = fish[i].in_front && p.z > 0.0;
      }
    }
    int width = 0, height = 0;
    const std::vector<std::uint16_t> mask =
        read_mask(out + "/masks/frame_00000" + std::to_string(frame) + ".png", width, height);
    ASSERT_EQ(width, 320);
    ASSERT_EQ(height, 180);
    std::vector<const nlohmann::json*> annotation_of(16, nullptr);
    for (const nlohmann::json& a : coco["annotations"]) {
      if (a["image_id"] != frame + 1) continue;
      const std::size_t id = a["fish_id"];
      ASSERT_LT(id, 16u);
      EXPECT_EQ(annotation_of[id], nullptr) << "two annotations of fish " << id;
      annotation_of[id] = &a;
    }
    for (std::size_t i = 0; i < 16; ++i) {
      SCOPED_TRACE("fish " + std::to_string(i));
      // Where the fish lies in the picture, and whether another fish's box overlaps it.
      const Projection& p = fish[i];
      const bool in_view =
          p.in_front && p.high.x > 0.0 && p.low.x < width && p.high.y > 0.0 && p.low.y < height;
      bool alone = true;
      for (std::size_t j = 0; j < 16; ++j) {
        if (j != i && fish[j].low.x < p.high.x + 1 && p.low.x < fish[j].high.x + 1 &&
            fish[j].low.y < p.high.y + 1 && p.low.y < fish[j].high.y + 1) {
          alone = false;
        }
      }
      std::size_t pixels = 0;
      glm::ivec2 box_low(1 << 30), box_high(-1);
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          if (mask[std::size_t(y * width + x)] != i + 1) continue;
          ++pixels;
          box_low = glm::min(box_low, glm::ivec2(x, y));
          box_high = glm::max(box_high, glm::ivec2(x, y));
          // A pixel of the fish has its centre inside the fish's projected vertices' box.
          EXPECT_GE(x + 0.5, p.low.x - 1e-3);
          EXPECT_LE(x + 0.5, p.high.x + 1e-3);
          EXPECT_GE(y + 0.5, p.low.y - 1e-3);
          EXPECT_LE(y + 0.5, p.high.y + 1e-3);
        }
      }
      const nlohmann::json* a = annotation_of[i];
      // Every fish seen has an annotation, and no annotation is empty.
      EXPECT_EQ(a != nullptr, pixels > 0);
      if (in_view && alone) {
        EXPECT_GT(pixels, 0u) << "a fish in view with nothing in front";
      }
      if (a == nullptr) continue;
      EXPECT_EQ((*a)["area"], pixels);
      EXPECT_EQ((*a)["bbox"], nlohmann::json({box_low.x, box_low.y, box_high.x - box_low.x + 1,
                                              box_high.y - box_low.y + 1}));
      if (alone && p.low.x > 1 && p.low.y > 1 && p.high.x < width - 1 && p.high.y < height - 1) {
        // Nothing in front and inside the frame: the box is the projection's, to a pixel.
        EXPECT_NEAR(box_low.x + 0.5, p.low.x, 1.5);
        EXPECT_NEAR(box_low.y + 0.5, p.low.y, 1.5);
        EXPECT_NEAR(box_high.x + 0.5, p.high.x, 1.5);
        EXPECT_NEAR(box_high.y + 0.5, p.high.y, 1.5);
      }
      // The keypoints are their vertices projected: the snout, the tail fork, and the
      // rig's parts (the caudal fin's tips, the pectoral fins' tips).
      const nlohmann::json& k = (*a)["keypoints"];
      ASSERT_EQ(k.size(), 3 * pictures::kKeypointCount);
      for (std::size_t n = 0; n < pictures::kKeypointCount; ++n) {
        ASSERT_TRUE(marks.keypoints[n].has_value()) << pictures::kKeypointNames[n];
        const glm::dvec3 point = project(tank.positions[i * vertices + *marks.keypoints[n]]);
        EXPECT_NEAR((*a)["keypoints_camera_m"][n][2].get<double>(), point.z, 1e-5);
        if (k[3 * n + 2] == 0) continue;
        EXPECT_NEAR(k[3 * n].get<double>(), point.x, 1e-3) << pictures::kKeypointNames[n];
        EXPECT_NEAR(k[3 * n + 1].get<double>(), point.y, 1e-3) << pictures::kKeypointNames[n];
      }
    }
  }
}

// The Python that has pycocotools: FINFLEX_TEST_PYTHON from the environment, else the
// virtual environment scripts/install-deps.sh makes; empty when neither works.
std::string coco_python() {
  const char* given = std::getenv("FINFLEX_TEST_PYTHON");
  const std::string python = given != nullptr ? given : FINFLEX_TEST_PYTHON;
  const std::string probe = "'" + python + "' -c 'import pycocotools, PIL, numpy' >/dev/null 2>&1";
  return std::system(probe.c_str()) == 0 ? python : "";
}

TEST(CliPictures, TheDatasetLoadsWithPycocotools) {
  const std::string python = coco_python();
  if (python.empty()) {
    // CI sets FINFLEX_REQUIRE_PYCOCOTOOLS: there the check must run.
    if (std::getenv("FINFLEX_REQUIRE_PYCOCOTOOLS") != nullptr) {
      FAIL() << "no Python with pycocotools (run scripts/install-deps.sh)";
    }
    GTEST_SKIP() << "no Python with pycocotools: scripts/install-deps.sh makes .venv";
  }
  // Two species, seen obliquely: fish hide each other. With the YOLO datasets, the
  // WebDataset shards, the depth maps, a stereo pair, a lens with noise and each frame
  // its own water and light, which
  // check_truth.py reads against coco.json (the lens undone there by its own code of
  // OpenCV's model).
  const std::string out = test::temp_path("coco");
  const RunResult r = run_cli(
      "swim --fish 40 --seconds 0.1 --fps 20 --seed 3 --size 320x180 --annotate --video none "
      "--formats coco,yolo,webdataset --depth --stereo 0.12 --distortion -0.2,0.05,0.001,-0.0005,0 "
      "--noise 2,4 --vary-optics --length-weight barramundi:0.012,2.98 --species " +
      low_resolution_species() + " --species " + fish("barramundi/BarramundiFish.gltf") + ":" +
      test::data_path("rigs/barramundi_swim.rig.json") + " --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto check = [&](const std::string& script, const std::string& folder) {
    const std::string log = test::temp_path("check.txt");
    const int status = std::system(
        ("'" + python + "' '" + script + "' '" + folder + "' >'" + log + "' 2>&1").c_str());
    return RunResult{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(log), ""};
  };
  const RunResult coco = check(FINFLEX_CHECK_COCO, out);
  EXPECT_EQ(coco.exit_code, 0) << coco.out;
  EXPECT_NE(coco.out.find("4 images"), std::string::npos) << coco.out;  // 2 stereo pairs
  EXPECT_NE(coco.out.find("all agree"), std::string::npos) << coco.out;
  const RunResult truth = check(FINFLEX_CHECK_TRUTH, out);
  EXPECT_EQ(truth.exit_code, 0) << truth.out;
  EXPECT_NE(truth.out.find("agree with coco.json"), std::string::npos) << truth.out;
  EXPECT_NE(truth.out.find("stereo: 2 pairs"), std::string::npos) << truth.out;
  EXPECT_NE(truth.out.find("webdataset: 1 shard(s), 4 samples"), std::string::npos) << truth.out;
  std::printf("%s", truth.out.c_str());

  // Seen from above through the water surface, and from the camera in the water behind
  // its flat port (through air, the window and the water): the floor's depth against
  // rays bent by Snell's law in check_truth.py, the keypoints on their fish.
  for (const auto& [camera, interface] :
       {std::pair{"--camera above", "surface"},
        std::pair{"--camera underwater --port 0.03,0.012,1.52", "port"}}) {
    SCOPED_TRACE(camera);
    const std::string refracted = test::temp_path(std::string("refracted-") + interface);
    const RunResult bent = run_cli(
        "swim --fish 40 --seconds 0.05 --fps 20 --seed 3 --size 320x180 --annotate --video none "
        "--formats coco,yolo --depth --refraction " +
        std::string(camera) + " --species " + low_resolution_species() + " --out '" + refracted +
        "'");
    ASSERT_EQ(bent.exit_code, 0) << bent.err;
    const RunResult bent_coco = check(FINFLEX_CHECK_COCO, refracted);
    EXPECT_EQ(bent_coco.exit_code, 0) << bent_coco.out;
    const RunResult bent_truth = check(FINFLEX_CHECK_TRUTH, refracted);
    EXPECT_EQ(bent_truth.exit_code, 0) << bent_truth.out;
    EXPECT_NE(bent_truth.out.find(std::string("refracted at the ") + interface), std::string::npos)
        << bent_truth.out;
    std::printf("%s", bent_truth.out.c_str());
  }
}

// Runs `arguments` expecting exit 2 with one line holding `expected`, and nothing at
// `out` or next to it.
void expect_refused(const std::string& arguments, const std::string& expected,
                    const std::string& out, const std::string& environment = "") {
  SCOPED_TRACE(arguments);
  const RunResult r = run_cli(arguments, environment);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  std::size_t left = 0;
  if (fs::is_directory(fs::path(out).parent_path())) {
    for (const auto& entry : fs::directory_iterator(fs::path(out).parent_path())) {
      left += entry.path().filename().string().find(".partial") != std::string::npos;
    }
  }
  EXPECT_EQ(left, 0u) << "a staging folder was left";
}

TEST(CliPictures, BadPictureInputsExitTwoAndWriteNothing) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --size 0x90", "--size '0x90'"},
      {" --size 160", "--size '160'"},
      {" --size 20000x90", "--size"},
      {" --camera top", "--camera 'top'"},
      {" --samples 0", "--samples '0'"},
      {" --video avi", "'avi' is not a video format"},
      {" --image-frames 99", "--image-frames '99'"},
      {" --annotate --image-frames none", "--annotate annotates the frames written as images"},
      {" --annotate --formats coco,xml", "--formats: 'xml' is not a dataset format"},
      {" --depth", "--depth is part of the dataset: it needs --annotate"},
      {" --stereo 0", "--stereo '0'"},
      {" --distortion 0.1,0.2", "--distortion '0.1,0.2': 5 numbers expected, 2 given"},
      {" --distortion 0.1,x,0,0,0", "--distortion '0.1,x,0,0,0': 'x' is not a finite number"},
      {" --distortion -5,0,0,0,0", "--distortion: the distortion does not invert"},
      {" --noise -1,0", "--noise -1,0: each sigma is 0 to 255"},
      {" --turbidity -1", "--turbidity -1: 0 to 100 NTU expected"},
      {" --dissolved 21", "--dissolved 21: 0 to 20 per metre expected"},
      {" --water muddy", "--water 'muddy' is not a water type (clear, ras, turbid)"},
      {" --vary-optics --turbidity 2", "--turbidity with --vary-optics"},
      {" --refraction --camera side", "--refraction bends the view rays at the water surface"},
      {" --port 0.02,0.01,1.49", "--port is the underwater camera's housing"},
      {" --camera underwater --refraction --port 0.02,0.01,3", "the refractive index is 1 to 2"},
      {" --camera underwater --tanks 2", "--camera underwater is in one tank's water"},
      {" --annotate --keypoints snout,eye", "--keypoints: 'eye' is not a keypoint (snout, "},
      {" --annotate --keypoints snout,left_pectoral_tip", "go together"},
      {" --keypoints snout", "--keypoints is part of the dataset"},
      {" --annotate --length-weight nosuch:0.01,3", "--length-weight: no species 'nosuch'"},
      {" --annotate --length-weight blub:0.01,5", "2 <= b <= 4"},
      {" --annotate --length-weight 0.01,3", "SPECIES:A,B expected"},
      {" --length-weight blub:0.01,3", "--length-weight is part of the dataset"},
      {" --stereo 11", "--stereo 11: a baseline above 10 m"},
      {" --formats yolo", "--formats is part of the dataset"},
      {" --no-render --video apng", "--video draws frames"},
      {" --draw some", "--draw 'some' is not a way to draw (expected all or written)"},
      {" --no-render --draw written", "--draw written draws the frames written: it needs --out"},
      {" --hand-off sideways",
       "--hand-off: 'sideways' is not auto, external-memory, shared or copy"},
      // PoCL has no GL sharing: asked for, the path that cannot run is named.
      {" --hand-off shared", "--hand-off shared: "},
      // Errors found once the renderer is up (test_cli has them without it).
      {" --tank 0.5,0.5", "tank.diameter"},
      {" --species " + fish(kLowResolutionBlub) + ":" +
           test::data_path("rigs/blub_low_resolution.rig.json"),
       "needs a body"},
      {" --device no-such-device", "no-such-device"},
  };
  for (const auto& [arguments, expected] : cases) {
    const std::string out = test::temp_path("never");
    expect_refused(small_swim() + arguments + " --out '" + out + "'", expected, out);
  }
  // A rig whose tail is not named caudal_fin: no caudal tips to ask for.
  std::string rig = read_text(test::data_path("rigs/blub_low_resolution_swim.rig.json"));
  for (std::size_t at; (at = rig.find("\"caudal_fin\"")) != std::string::npos;) {
    rig.replace(at, 12, "\"tail\"");
  }
  const std::string tailless = test::temp_path("tailless.rig.json");
  { std::ofstream(tailless) << rig; }
  const std::string untailed = test::temp_path("untailed");
  expect_refused(
      "swim --fish 4 --seconds 0.1 --fps 30 --annotate --keypoints snout,caudal_upper_tip "
      "--species " +
          fish(kLowResolutionBlub) + ":" + tailless + " --out '" + untailed + "'",
      "--keypoints: no species' rig has caudal_upper_tip (it comes from a part named "
      "caudal_fin)",
      untailed);
  const std::string fast = test::temp_path("fast");
  expect_refused("swim --fish 4 --seconds 0.01 --fps 1000 --species " + low_resolution_species() +
                     " --out '" + fast + "'",
                 "a video plays at 1 to 240", fast);
  const std::string nowhere = test::temp_path("nowhere");
  expect_refused(small_swim() + " --annotate", "--annotate needs --out", nowhere);
  expect_refused(small_swim("70000") + " --annotate --out '" + nowhere + "'",
                 "masks hold 16-bit ids", nowhere);
  // An output folder whose parent is a file, or not writable.
  const std::string file = test::temp_path("a_file");
  { std::ofstream(file) << "keep\n"; }
  expect_refused(small_swim() + " --out '" + file + "/sub'", "does not exist", file + "/sub");
  EXPECT_EQ(read_text(file), "keep\n");
  if (geteuid() != 0) {  // root writes anywhere
    const std::string locked = fs::path(test::temp_path("locked")).parent_path().string() + "/ro";
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    expect_refused(small_swim() + " --out '" + locked + "/out'", "cannot write", locked + "/out");
    fs::permissions(locked, fs::perms::owner_all);
  }
  // No EGL device or display: GLVND finds no vendor library.
  expect_refused(small_swim() + " --out '" + nowhere + "'", "no EGL device", nowhere,
                 "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json");
  // An existing output folder keeps what it holds when a run fails.
  const std::string kept = test::temp_path("kept");
  fs::create_directories(kept);
  { std::ofstream(kept + "/notes.txt") << "mine\n"; }
  const RunResult r = run_cli(small_swim() + " --out '" + kept + "'",
                              "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(files_in(kept), 1u);
  EXPECT_EQ(read_text(kept + "/notes.txt"), "mine\n");
}

TEST(CliPictures, BakeWritesEveryFormatIntoTheFolder) {
  const std::string out = test::temp_path("bake");
  fs::create_directories(out);
  { std::ofstream(out + "/notes.txt") << "mine\n"; }
  const RunResult r = run_cli("bake --species " + low_resolution_species() +
                              " --frames 6 --length 0.3 --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("in 6 frames"), std::string::npos) << r.out;
  for (const char* file : {"blub_low_resolution_swim.glb", "blub_low_resolution_vat_positions.png",
                           "blub_low_resolution_vat_normals.png", "blub_low_resolution_vat.json",
                           "blub_low_resolution_vat.glsl", "blub_low_resolution_vat_mesh.glb",
                           "bake.json", "notes.txt"}) {
    EXPECT_TRUE(fs::is_regular_file(out + "/" + file)) << file;
  }
  EXPECT_EQ(files_in(out + "/meshes"), 6u);
  const nlohmann::json bake = read_json(out + "/bake.json");
  EXPECT_EQ(bake["frames"], 6);
  EXPECT_NEAR(bake["frame_dt_s"].get<double>() * 6.0, bake["period_s"].get<double>(), 1e-12);
  EXPECT_NEAR(bake["tail_beat_hz"].get<double>() * bake["period_s"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(read_text(out + "/notes.txt"), "mine\n");
}

TEST(CliPictures, BadBakeInputsExitTwoAndWriteNothing) {
  const std::string species = " --species " + low_resolution_species();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {species + " --frames 1", "--frames '1'"},
      {species + " --length 0", "--length '0'"},
      {species + " --speed -1", "--speed '-1'"},
      {species + " --speed 50", "speed = 50"},
      {species + " --formats gltf,fbx", "'fbx' is not a bake"},
      {species + " --mesh-format dae", "--mesh-format 'dae'"},
      {species + " --vat-width 0", "--vat-width '0'"},
      {species + " --normals smooth", "--normals"},
      {" --species nocolon", "MESH:RIG"},
      {" --species /nonexistent.obj:x.rig.json", "/nonexistent.obj"},
      {species + " --device no-such-device", "no-such-device"},
  };
  for (const auto& [arguments, expected] : cases) {
    const std::string out = test::temp_path("never");
    expect_refused("bake" + arguments + " --out '" + out + "'", expected, out);
  }
  expect_refused("bake" + species, "--out is required", test::temp_path("none"));
  const std::string file = test::temp_path("a_file");
  { std::ofstream(file) << "keep\n"; }
  expect_refused("bake" + species + " --out '" + file + "'", "is not a folder", file + "/x");
  EXPECT_EQ(read_text(file), "keep\n");
}

}  // namespace
}  // namespace finflex

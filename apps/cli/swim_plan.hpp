// finflex swim's options as typed and the plan they make, every value checked against
// the others before anything runs: counts, the species' files, the tank, the pictures
// (size, camera, frames, videos, the dataset) and the output folder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "swim_pictures.hpp"
#include "swim_scene.hpp"
#include "tank_pictures.hpp"

namespace finflex::cli {

struct SwimOptions {
  std::string fish = "1000";
  std::string seconds = "10";
  std::string fps = "30";
  std::vector<std::string> species;
  std::string tank;
  std::string tanks = "1";
  std::string seed = "1";
  std::string normals = "jacobian";
  std::string device;
  std::string out;
  std::string mesh_frames;
  std::string size = "640x360";
  std::string camera = "oblique";
  std::string stereo;                       // empty: one camera
  std::string distortion;                   // k1,k2,p1,p2,k3; empty: none
  std::string noise;                        // READ,SHOT; empty: none
  std::vector<std::string> length_weights;  // SPECIES:A,B
  std::string water = "ras";                // a water type (frame_optics.hpp)
  std::string turbidity;                    // NTU; empty: the water type's
  std::string dissolved;                    // a_g(440) per metre; empty: the water type's
  bool vary_optics = false;                 // each frame its own water and light
  bool refraction = false;                  // view rays bend at the surface or the port
  std::string port;                         // DISTANCE,THICKNESS,INDEX; empty: FlatPort's
  std::string samples = "4";
  std::string image_frames;
  std::string video;
  bool annotate = false;
  std::string formats = "coco";  // with --annotate: coco, yolo
  std::string keypoints;         // with --annotate: a list of them; empty: all
  bool depth = false;
  int render = -1;  // --render: 1, --no-render: 0, neither: -1 (on with --out)
  std::string hand_off = "auto";
  std::string draw = "all";  // all, written
  bool reference_draw = false;
  std::string levels;  // empty: every fish at full detail
  std::string pixel_budget = "1";
  std::string triangle_ratio = "0.5";
  bool freeze_fins = true;
  bool wall_occlusion = true;
};

// What the command runs, every value checked.
struct SwimPlan {
  std::size_t fish = 0;
  std::size_t frames = 0;
  double fps = 0.0;
  std::vector<tank::SpeciesFiles> species;
  tank::HallSettings hall;  // one tank unless --tanks
  std::uint64_t seed = 0;
  NormalMode normals = NormalMode::kJacobian;
  std::set<std::size_t> mesh_frames;
  bool render = false;
  std::optional<pictures::HandOffPath> hand_off;  // nullopt: the first that can run
  bool reference_draw = false;                    // each frame also the reference draw
  bool draw_written = false;  // --draw written: only the frames written (and the first)
  pictures::PictureSettings pictures;
  PictureFiles files;
  // --levels: levels of detail and culling, chosen from the pictures' camera.
  std::optional<tank::SceneLevels> levels;
};

// The plan of `options`. finflex::Error (kInvalidArgument or kIo) naming the option and
// the value for the first one at fault; nothing is created.
SwimPlan plan_of(const SwimOptions& options);

}  // namespace finflex::cli

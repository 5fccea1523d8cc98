// finflex bake: one swim cycle of one fish for engines that cannot run OpenCL (Unity,
// Unreal, Godot, three.js, Blender): glTF morph-target animation, vertex animation
// textures and per-frame meshes (apps/bake/), from the engine's own deformation.
//
//   finflex bake --out DIR [--species MESH:RIG] [--frames N] [--length M] [--speed S]
//                [--formats gltf,vat,meshes] [--mesh-format obj|ply|off|stl|gltf|glb]
//                [--vat-width W] [--normals rotate|jacobian] [--device NAME]
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "frame_meshes.hpp"
#include "morph_animation.hpp"
#include "staging_folder.hpp"
#include "swim_cycle.hpp"
#include "swim_scene.hpp"
#include "vertex_animation_texture.hpp"

namespace finflex::cli {
namespace {

namespace fs = std::filesystem;

struct BakeOptions {
  std::string out;
  std::string species;
  std::string frames = "24";
  std::string length = "0.4";
  std::string speed = "1";
  std::string formats = "gltf,vat,meshes";
  std::string mesh_format = "obj";
  std::string vat_width = "4096";
  std::string normals = "jacobian";
  std::string device;
};

struct BakePlan {
  tank::SpeciesFiles species;
  bake::CycleSettings cycle;
  bool gltf = false;
  bool vat = false;
  bool meshes = false;
  std::string mesh_format;
  std::size_t vat_width = 0;
};

BakePlan plan_of(const BakeOptions& options) {
  BakePlan plan;
  if (options.out.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--out", "--out is required: the folder to write");
  }
  plan.species = options.species.empty() ? tank::bundled_species(FINFLEX_DATA_DIR).front()
                                         : tank::parse_species(options.species, "--species");
  for (const std::string& path : {plan.species.mesh, plan.species.rig}) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      throw Error(ErrorCode::kIo, "--species", "--species: '" + path + "' is not a file");
    }
  }
  plan.cycle.frames = parse_count(options.frames, "--frames", 2, 10000);
  plan.cycle.length_m = parse_positive(options.length, "--length");
  plan.cycle.speed = parse_positive(options.speed, "--speed", /*zero_allowed=*/true);
  for_option("--speed", [&] { plan.cycle.validate(); });
  plan.cycle.normals = parse_normal_mode(options.normals, "--normals");
  std::size_t begin = 0;
  while (begin <= options.formats.size()) {
    const std::size_t comma = std::min(options.formats.find(',', begin), options.formats.size());
    const std::string item = options.formats.substr(begin, comma - begin);
    begin = comma + 1;
    if (item == "gltf") {
      plan.gltf = true;
    } else if (item == "vat") {
      plan.vat = true;
    } else if (item == "meshes") {
      plan.meshes = true;
    } else {
      throw Error(ErrorCode::kInvalidArgument, "--formats",
                  "--formats '" + options.formats + "': '" + item +
                      "' is not a bake (a list of gltf, vat, meshes)");
    }
  }
  const std::vector<std::string> mesh_formats = {"obj", "ply", "off", "stl", "gltf", "glb"};
  if (std::find(mesh_formats.begin(), mesh_formats.end(), options.mesh_format) ==
      mesh_formats.end()) {
    throw Error(ErrorCode::kInvalidArgument, "--mesh-format",
                "--mesh-format '" + options.mesh_format +
                    "' is not a mesh format (obj, ply, off, stl, gltf, glb)");
  }
  plan.mesh_format = options.mesh_format;
  plan.vat_width = parse_count(options.vat_width, "--vat-width", 1, 16384);
  check_output_folder(options.out, "--out");
  return plan;
}

int run_bake(const BakeOptions& options) {
  try {
    const BakePlan plan = plan_of(options);
    const std::string stem = tank::species_name(plan.species);
    const Mesh mesh = load_mesh(plan.species.mesh);
    const SwimModel swim(RiggedMesh(mesh, resolve_rig(load_rig_file(plan.species.rig), mesh)));
    Context context(options.device);
    const bake::BakedCycle baked = bake::bake_cycle(context, swim, plan.cycle);

    StagingFolder staging(options.out, "--out");
    const fs::path folder(staging.path());
    nlohmann::ordered_json summary;
    summary["species"] = stem;
    summary["mesh"] = plan.species.mesh;
    summary["rig"] = plan.species.rig;
    summary["vertex_count"] = mesh.vertex_count();
    summary["length_m"] = plan.cycle.length_m;
    summary["speed_body_lengths_per_s"] = plan.cycle.speed;
    summary["tail_beat_hz"] = baked.cycle.frequency_hz;
    summary["period_s"] = baked.cycle.period_s;
    summary["frames"] = baked.cycle.frames;
    summary["frame_dt_s"] = baked.cycle.dt_s;
    summary["device"] = context.description().device_name;
    summary["frame_space"] = "metres; y up; the head towards +z; the pivot at the origin";
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    if (plan.gltf) {
      bake::write_morph_animation((folder / (stem + "_swim.glb")).string(), stem, mesh, baked);
      files.push_back(stem + "_swim.glb");
    }
    if (plan.vat) {
      bake::write_vertex_animation_texture(folder.string(), stem, mesh, baked, plan.vat_width);
      for (const char* suffix :
           {"_vat_positions.png", "_vat_normals.png", "_vat.json", "_vat.glsl", "_vat_mesh.glb"}) {
        files.push_back(stem + suffix);
      }
    }
    if (plan.meshes) {
      fs::create_directories(folder / "meshes");
      bake::write_frame_meshes((folder / "meshes").string(), stem, plan.mesh_format, mesh, baked);
      files.push_back("meshes/");
    }
    summary["files"] = files;
    {
      std::ofstream out(folder / "bake.json");
      out << summary.dump(1) << "\n";
      if (!out)
        throw Error(ErrorCode::kIo, "--out", "'" + options.out + "/bake.json': write failed");
    }
    staging.commit();
    std::printf(
        "baked one swim cycle of %s (%zu vertices): %.3g m at %.3g body lengths/s, tail beat "
        "%.3g Hz, period %.4g s in %zu frames (dt %.4g s) on %s\nwrote %s\n",
        stem.c_str(), mesh.vertex_count(), plan.cycle.length_m, plan.cycle.speed,
        baked.cycle.frequency_hz, baked.cycle.period_s, baked.cycle.frames, baked.cycle.dt_s,
        context.description().device_name.c_str(), options.out.c_str());
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("bake", error.what());
  }
}

}  // namespace

Command add_bake_command(CLI::App& app) {
  auto options = std::make_shared<BakeOptions>();
  CLI::App* bake = app.add_subcommand(
      "bake",
      "One swim cycle of one fish as glTF morph animation, vertex animation textures "
      "and per-frame meshes");
  bake->add_option("--out", options->out, "Folder to write (made; its parent must exist)");
  bake->add_option("--species", options->species,
                   "MESH:RIG, a mesh and its swim rig (default: the bundled Blub)");
  bake->add_option("--frames", options->frames, "Frames over one tail beat")->capture_default_str();
  bake->add_option("--length", options->length, "The fish's length, metres")->capture_default_str();
  bake->add_option("--speed", options->speed, "Swimming speed, body lengths per second")
      ->capture_default_str();
  bake->add_option("--formats", options->formats, "Any of gltf, vat, meshes")
      ->capture_default_str();
  bake->add_option("--mesh-format", options->mesh_format,
                   "Per-frame mesh files: obj, ply, off, stl, gltf or glb")
      ->capture_default_str();
  bake->add_option("--vat-width", options->vat_width,
                   "Largest width of the vertex animation textures, texels")
      ->capture_default_str();
  bake->add_option("--normals", options->normals, "rotate or jacobian")->capture_default_str();
  bake->add_option("--device", options->device,
                   "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  return {[options] { plan_of(*options); }, [options] { return run_bake(*options); }};
}

}  // namespace finflex::cli

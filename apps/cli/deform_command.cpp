// finflex deform: bend one mesh file and write the result.
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct DeformOptions {
  std::string in;
  std::string out;
  std::string m;
  std::string mode;  // empty: paper
  std::string normals = "rotate";
  std::string frame;             // empty: auto
  std::string rig;               // a rig file instead of --m
  std::vector<std::string> set;  // NAME=VALUE rig parameters
  std::string path = "auto";
  bool clamp = false;
  std::string device;
  std::string head;  // "X,Y,Z" overrides of the automatic frame
  std::string dorsal;
  std::string pivot;
};

// Parses "X,Y,Z" (empty: not given).
std::optional<glm::dvec3> parse_vector(const std::string& text, const std::string& option) {
  if (text.empty()) return std::nullopt;
  glm::dvec3 value;
  std::size_t begin = 0;
  for (int c = 0; c < 3; ++c) {
    const std::size_t comma = text.find(',', begin);
    const bool last = c == 2;
    if (last != (comma == std::string::npos)) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  option + " '" + text + "' is not three comma-separated numbers X,Y,Z");
    }
    value[c] = parse_number(text.substr(begin, last ? std::string::npos : comma - begin), option);
    begin = comma + 1;
  }
  return value;
}

FrameOptions frame_options(const DeformOptions& options) {
  FrameOptions frame;
  frame.head_direction = parse_vector(options.head, "--head");
  frame.dorsal_direction = parse_vector(options.dorsal, "--dorsal");
  frame.pivot = parse_vector(options.pivot, "--pivot");
  if (options.frame == "identity" &&
      (frame.head_direction || frame.dorsal_direction || frame.pivot)) {
    throw Error(
        ErrorCode::kInvalidArgument, "--frame",
        "--head, --dorsal and --pivot adjust the automatic frame: not with --frame identity");
  }
  return frame;
}

// The option that gave a frame override the library refused ("options.pivot").
std::string frame_option(const Error& error) {
  if (error.field() == "options.head_direction") return "--head";
  if (error.field() == "options.dorsal_direction") return "--dorsal";
  if (error.field() == "options.pivot") return "--pivot";
  return "";
}

BodyFrame choose_frame(const Mesh& mesh, const std::string& frame, const FrameOptions& options) {
  if (frame == "identity") return BodyFrame::identity();
  try {
    return find_body_frame(mesh, options);
  } catch (const Error& error) {
    const std::string option = frame_option(error);
    if (option.empty()) throw;
    throw Error(error.code(), option, option + ": " + error.what());
  }
}

// Deforms one instance of `model` with `values` on the device into `bent`; returns
// the execution path that ran.
RigPath deform_once(Context& context, const RiggedMesh& model, const RigParameters& values,
                    NormalMode normals, RigPath path, bool clamp, Mesh& bent) {
  ClDeformer deformer(context, model);
  DeviceBatch batch = deformer.allocate(1);
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = normals;
  job.clamp = clamp;
  job.path = path;
  job.outputs = &batch;
  deformer.enqueue(job);
  bent = instance_mesh(model.mesh(), deformer.read(batch), 0);
  return path == RigPath::kAuto ? deformer.automatic_path() : path;
}

// The plain bend of the whole body: --m, --mode, --frame.
std::string bend_whole_body(const DeformOptions& options, const Mesh& rest, NormalMode normals,
                            Context& context, Mesh& bent) {
  if (options.m.empty())
    throw Error(ErrorCode::kInvalidArgument, "--m", "--m is required (or --rig)");
  const double m = parse_number(options.m, "--m");
  const BendMode mode = parse_bend_mode(options.mode.empty() ? "paper" : options.mode, "--mode");
  const FrameOptions frame = frame_options(options);
  const RiggedMesh model =
      RiggedMesh::single_bend(rest, choose_frame(rest, options.frame, frame), mode);
  RigParameters values(model, 1);
  values.set(0, "m", static_cast<float>(m));
  float used = 0.0f;  // m as checked (and clamped)
  for_option("--m", [&] { check_parameters(model.rig(), values.view(), options.clamp, &used); });
  deform_once(context, model, values, normals, RigPath::kAuto, options.clamp, bent);
  char summary[160];
  std::snprintf(summary, sizeof summary, "m = %g (%s bend, %s normals, x_max %.4f)",
                static_cast<double>(used), to_string(mode), to_string(normals),
                model.rig().components[0].chain[0].geometry.x_max);
  return summary;
}

// Parses "NAME=VALUE"; VALUE must fit a float (parameters are float32).
std::pair<std::string, float> parse_assignment(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw Error(ErrorCode::kInvalidArgument, "--set", "--set '" + text + "' is not NAME=VALUE");
  }
  const std::string name = text.substr(0, equals);
  const std::string value = text.substr(equals + 1);
  const double number = parse_number(value, "--set " + name);
  if (std::isfinite(number) && std::abs(number) > std::numeric_limits<float>::max()) {
    throw Error(ErrorCode::kOutOfRange, "--set " + name,
                "--set " + name + " '" + value + "' is beyond the range of a float");
  }
  return {name, static_cast<float>(number)};
}

// The options that go with --rig, or with the whole-body bend (--m): everything but the
// files' contents.
void check_deform(const DeformOptions& options) {
  parse_normal_mode(options.normals, "--normals");
  check_input_file("--in", options.in, mesh_extensions());
  check_output_file("--out", options.out, mesh_extensions());
  if (options.rig.empty()) {
    if (!options.set.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--set", "--set needs --rig");
    }
    if (options.m.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--m", "--m is required (or --rig)");
    }
    parse_number(options.m, "--m");
    parse_bend_mode(options.mode.empty() ? "paper" : options.mode, "--mode");
    frame_options(options);
    return;
  }
  const std::pair<const char*, const std::string*> plain_bend_only[] = {
      {"--m", &options.m},       {"--mode", &options.mode},     {"--frame", &options.frame},
      {"--head", &options.head}, {"--dorsal", &options.dorsal}, {"--pivot", &options.pivot}};
  for (const auto& [option, value] : plain_bend_only) {
    if (!value->empty()) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  std::string(option) + " does not go with --rig: the rig file says it");
    }
  }
  parse_rig_path(options.path, "--path");
  check_input_file("--rig", options.rig);
  for (const std::string& assignment : options.set) parse_assignment(assignment);
}

// A rigged deformation: --rig, --set, --path.
std::string deform_rig(const DeformOptions& options, const Mesh& rest, NormalMode normals,
                       Context& context, Mesh& bent) {
  const RigPath path = parse_rig_path(options.path, "--path");
  const RiggedMesh model(
      rest, resolve_rig(for_option("--rig", [&] { return load_rig_file(options.rig); }), rest));
  RigParameters values(model, 1);
  for (const std::string& assignment : options.set) {
    const auto [name, value] = parse_assignment(assignment);
    for_option("--set", [&, name = name, value = value] { values.set(0, name, value); });
  }
  const RigPath ran = deform_once(context, model, values, normals, path, options.clamp, bent);
  std::string summary = "rig " + options.rig + " (" +
                        std::to_string(model.rig().components.size()) + " components, " +
                        to_string(ran) + " path, " + to_string(normals) + " normals)";
  for (std::size_t p = 0; p < model.rig().parameters.size(); ++p) {
    char value[64];
    std::snprintf(value, sizeof value, "%s%s = %g", p == 0 ? ": " : ", ",
                  model.rig().parameters[p].name.c_str(), static_cast<double>(values.get(0, p)));
    summary += value;
  }
  return summary;
}

// After check_deform: the device, then the files.
int run_deform(const DeformOptions& options) {
  try {
    const NormalMode normals = parse_normal_mode(options.normals, "--normals");
    Context context(options.device);
    const Mesh rest = for_option("--in", [&] { return load_mesh(options.in); });
    Mesh bent;
    const std::string what = options.rig.empty()
                                 ? bend_whole_body(options, rest, normals, context, bent)
                                 : deform_rig(options, rest, normals, context, bent);
    for_option("--out", [&] { save_mesh(options.out, bent); });
    std::printf("bent %zu vertices with %s on %s -> %s\n", rest.vertex_count(), what.c_str(),
                context.description().device_name.c_str(), options.out.c_str());
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("deform", error.what());
  }
}

}  // namespace

Command add_deform_command(CLI::App& app) {
  auto options = std::make_shared<DeformOptions>();
  CLI::App* deform = app.add_subcommand(
      "deform", "Bend a mesh with the paper's fish bend, or deform it with a rig");
  deform->add_option("--in", options->in, "Input mesh (.obj .ply .off .stl .gltf .glb)")
      ->required();
  deform->add_option("--out", options->out, "Output mesh; the format follows the extension")
      ->required();
  deform->add_option("--m", options->m, "Bend parameter m, |m| <= 0.5 / x_max (without --rig)");
  deform->add_option("--mode", options->mode, "paper (series (15)-(17), default) or exact (asin)");
  deform->add_option("--normals", options->normals, "rotate (the paper's (8)) or jacobian (exact)")
      ->capture_default_str();
  deform
      ->add_option(
          "--frame", options->frame,
          "auto (found from the mesh, default) or identity (mesh coordinates are the frame)")
      ->check(CLI::IsMember({"auto", "identity"}));
  deform->add_flag("--clamp", options->clamp, "Clamp m into its valid range instead of failing");
  deform->add_option("--head", options->head, "Automatic frame: X,Y,Z roughly towards the head");
  deform->add_option("--dorsal", options->dorsal,
                     "Automatic frame: X,Y,Z roughly towards the back");
  deform->add_option("--pivot", options->pivot,
                     "Automatic frame: the fixed point X,Y,Z (mesh units)");
  deform->add_option("--rig", options->rig, "Rig file (JSON, docs/rigs.md) instead of --m");
  deform->add_option("--set", options->set, "NAME=VALUE: a rig parameter (repeatable; unset: 0)")
      ->allow_extra_args(false);
  deform->add_option("--path", options->path, "With --rig: auto, fused or passes")
      ->capture_default_str();
  deform->add_option("--device", options->device,
                     "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  return {[options] { check_deform(*options); }, [options] { return run_deform(*options); }};
}

}  // namespace finflex::cli

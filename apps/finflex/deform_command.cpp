// finflex deform: bend one mesh file and write the result.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "finflex/cli_errors.hpp"
#include "finflex/commands.hpp"
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

// Library field names of what the command line calls by its option names.
std::string with_option_names(const Error& error) {
  static const std::pair<const char*, const char*> kNames[] = {
      {"m[0]", "--m"},
      {"options.head_direction", "--head"},
      {"options.dorsal_direction", "--dorsal"},
      {"options.pivot", "--pivot"},
  };
  std::string message = error.what();
  for (const auto& [library_name, option] : kNames) {
    const std::size_t at = message.find(library_name);
    if (error.field() == library_name && at != std::string::npos) {
      message.replace(at, std::string(library_name).size(), option);
    }
  }
  return message;
}

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

BodyFrame choose_frame(const Mesh& mesh, const std::string& frame, const FrameOptions& options) {
  if (frame == "identity") return BodyFrame::identity();
  return find_body_frame(mesh, options);
}

// Errors of a file operation name the option that gave the path.
template <typename Operation>
auto with_path_option(const std::string& option, Operation operation) {
  try {
    return operation();
  } catch (const Error& error) {
    throw Error(error.code(), option, option + ": " + error.what());
  }
}

// The plain bend of the whole body: --m, --mode, --frame.
std::string bend_whole_body(const DeformOptions& options, const Mesh& rest, NormalMode normals,
                            Context& context, Mesh& bent) {
  if (options.m.empty())
    throw Error(ErrorCode::kInvalidArgument, "--m", "--m is required (or --rig)");
  const double m = parse_number(options.m, "--m");
  const BendSettings settings{
      parse_bend_mode(options.mode.empty() ? "paper" : options.mode, "--mode"), normals};
  const FrameOptions frame = frame_options(options);
  const LocalMesh local = make_local_mesh(rest, choose_frame(rest, options.frame, frame));
  const std::vector<float> parameters =
      checked_bend_params({static_cast<float>(m)}, local.x_max, options.clamp);
  ClDeformer deformer(context, local);
  DeviceBatch batch = deformer.allocate(1);
  deformer.enqueue(parameters, settings, batch);
  bent = instance_mesh(rest, deformer.read(batch), 0);
  char summary[160];
  std::snprintf(summary, sizeof summary, "m = %g (%s bend, %s normals, x_max %.4f)",
                static_cast<double>(parameters[0]), to_string(settings.mode), to_string(normals),
                local.x_max);
  return summary;
}

// Parses "NAME=VALUE".
std::pair<std::string, float> parse_assignment(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw Error(ErrorCode::kInvalidArgument, "--set", "--set '" + text + "' is not NAME=VALUE");
  }
  const std::string name = text.substr(0, equals);
  return {name, static_cast<float>(parse_number(text.substr(equals + 1), "--set " + name))};
}

// A rigged deformation: --rig, --set, --path.
std::string deform_rig(const DeformOptions& options, const Mesh& rest, NormalMode normals,
                       Context& context, Mesh& bent) {
  const std::pair<const char*, const std::string*> plain_bend_only[] = {
      {"--m", &options.m},       {"--mode", &options.mode},     {"--frame", &options.frame},
      {"--head", &options.head}, {"--dorsal", &options.dorsal}, {"--pivot", &options.pivot}};
  for (const auto& [option, value] : plain_bend_only) {
    if (!value->empty()) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  std::string(option) + " does not go with --rig: the rig file says it");
    }
  }
  const RigPath path = parse_rig_path(options.path, "--path");
  const Rig rig =
      resolve_rig(with_path_option("--rig", [&] { return load_rig_file(options.rig); }), rest);
  RigParameters values(rig, 1);
  for (const std::string& assignment : options.set) {
    const auto [name, value] = parse_assignment(assignment);
    try {
      values.set(0, name, value);
    } catch (const Error& error) {
      throw Error(error.code(), "--set", "--set: " + std::string(error.what()));
    }
  }
  ClRigDeformer deformer(context, rest, rig);
  DeviceBatch batch = deformer.allocate(1);
  deformer.enqueue(values, normals, batch, path, options.clamp);
  bent = instance_mesh(rest, deformer.read(batch), 0);
  std::string summary = "rig " + options.rig + " (" + std::to_string(rig.components.size()) +
                        " components, " +
                        to_string(path == RigPath::kAuto ? deformer.automatic_path() : path) +
                        " path, " + to_string(normals) + " normals)";
  for (std::size_t p = 0; p < rig.params.size(); ++p) {
    char value[64];
    std::snprintf(value, sizeof value, "%s%s = %g", p == 0 ? ": " : ", ", rig.params[p].c_str(),
                  static_cast<double>(values.get(0, p)));
    summary += value;
  }
  return summary;
}

int run_deform(const DeformOptions& options) {
  try {
    // Everything that can be checked before reading a file is checked first.
    const NormalMode normals = parse_normal_mode(options.normals, "--normals");
    if (options.out.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--out", "--out is empty");
    }
    if (std::filesystem::is_directory(options.out)) {
      throw Error(ErrorCode::kInvalidArgument, "--out",
                  "--out '" + options.out + "' is a directory");
    }
    if (options.rig.empty() && !options.set.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--set", "--set needs --rig");
    }

    const Mesh rest = with_path_option("--in", [&] { return load_mesh(options.in); });
    Context context(options.device);
    Mesh bent;
    const std::string what = options.rig.empty()
                                 ? bend_whole_body(options, rest, normals, context, bent)
                                 : deform_rig(options, rest, normals, context, bent);
    with_path_option("--out", [&] { save_mesh(options.out, bent); });
    std::printf("bent %zu vertices with %s on %s -> %s\n", rest.vertex_count(), what.c_str(),
                context.description().device_name.c_str(), options.out.c_str());
    return kExitSuccess;
  } catch (const Error& error) {
    return fail("deform", with_option_names(error));
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
  return [options] { return run_deform(*options); };
}

}  // namespace finflex::cli

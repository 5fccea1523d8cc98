// finflex deform: bend one mesh file and write the result.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "finflex/cli_errors.hpp"
#include "finflex/commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct DeformOptions {
  std::string in;
  std::string out;
  std::string m;
  std::string mode = "paper";
  std::string normals = "rotate";
  std::string frame = "auto";
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

int run_deform(const DeformOptions& options) {
  try {
    // Everything that can be checked before reading a file is checked first.
    const double m = parse_number(options.m, "--m");
    const BendSettings settings{parse_bend_mode(options.mode, "--mode"),
                                parse_normal_mode(options.normals, "--normals")};
    if (options.out.empty()) {
      throw Error(ErrorCode::kInvalidArgument, "--out", "--out is empty");
    }
    if (std::filesystem::is_directory(options.out)) {
      throw Error(ErrorCode::kInvalidArgument, "--out",
                  "--out '" + options.out + "' is a directory");
    }

    const FrameOptions frame = frame_options(options);

    const Mesh rest = with_path_option("--in", [&] { return load_mesh(options.in); });
    const LocalMesh local = make_local_mesh(rest, choose_frame(rest, options.frame, frame));
    const std::vector<float> parameters =
        checked_bend_params({static_cast<float>(m)}, local.x_max, options.clamp);

    Context context(options.device);
    ClDeformer deformer(context, local);
    DeviceBatch batch = deformer.allocate(1);
    deformer.enqueue(parameters, settings, batch);
    const Mesh bent = instance_mesh(rest, deformer.read(batch), 0);
    with_path_option("--out", [&] { save_mesh(options.out, bent); });
    std::printf("bent %zu vertices with m = %g (%s bend, %s normals, x_max %.4f) on %s -> %s\n",
                rest.vertex_count(), static_cast<double>(parameters[0]), to_string(settings.mode),
                to_string(settings.normals), local.x_max, context.description().device_name.c_str(),
                options.out.c_str());
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
  CLI::App* deform = app.add_subcommand("deform", "Bend a mesh with the paper's fish bend");
  deform->add_option("--in", options->in, "Input mesh (.obj .ply .off .stl .gltf .glb)")
      ->required();
  deform->add_option("--out", options->out, "Output mesh; the format follows the extension")
      ->required();
  deform->add_option("--m", options->m, "Bend parameter m, |m| <= 0.5 / x_max")->required();
  deform->add_option("--mode", options->mode, "paper (series (15)-(17)) or exact (asin)")
      ->capture_default_str();
  deform->add_option("--normals", options->normals, "rotate (the paper's (8)) or jacobian (exact)")
      ->capture_default_str();
  deform
      ->add_option("--frame", options->frame,
                   "auto (found from the mesh) or identity (mesh coordinates are the frame)")
      ->check(CLI::IsMember({"auto", "identity"}))
      ->capture_default_str();
  deform->add_flag("--clamp", options->clamp, "Clamp m into its valid range instead of failing");
  deform->add_option("--head", options->head, "Automatic frame: X,Y,Z roughly towards the head");
  deform->add_option("--dorsal", options->dorsal,
                     "Automatic frame: X,Y,Z roughly towards the back");
  deform->add_option("--pivot", options->pivot,
                     "Automatic frame: the fixed point X,Y,Z (mesh units)");
  deform->add_option("--device", options->device,
                     "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  return [options] { return run_deform(*options); };
}

}  // namespace finflex::cli

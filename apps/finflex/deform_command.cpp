// finflex deform: bend one mesh file and write the result.
#include <filesystem>
#include <memory>
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
};

// The library names a single instance's parameter "m[0]"; on the command line it is --m.
std::string with_option_names(const Error& error) {
  std::string message = error.what();
  const std::string library_name = "m[0]";
  const std::size_t at = message.find(library_name);
  if (error.field() == library_name && at != std::string::npos) {
    message.replace(at, library_name.size(), "--m");
  }
  return message;
}

BodyFrame choose_frame(const Mesh& mesh, const std::string& frame) {
  if (frame == "identity") return BodyFrame::identity();
  return find_body_frame(mesh);
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
      throw Error(ErrorCode::kInvalidArgument, "--out", "--out '" + options.out + "' is a directory");
    }

    const Mesh rest = load_mesh(options.in);
    const LocalMesh local = make_local_mesh(rest, choose_frame(rest, options.frame));
    const std::vector<float> parameters =
        checked_bend_params({static_cast<float>(m)}, local.x_max, options.clamp);

    Context context(options.device);
    ClDeformer deformer(context, local);
    DeviceBatch batch = deformer.allocate(1);
    deformer.enqueue(parameters, settings, batch);
    save_mesh(options.out, instance_mesh(rest, deformer.read(batch), 0));
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
  deform->add_option("--in", options->in, "Input mesh (.obj .ply .off .stl .gltf .glb)")->required();
  deform->add_option("--out", options->out, "Output mesh; the format follows the extension")
      ->required();
  deform->add_option("--m", options->m, "Bend parameter m, |m| <= 0.5 / x_max")->required();
  deform->add_option("--mode", options->mode, "paper (series (15)-(17)) or exact (asin)")
      ->capture_default_str();
  deform->add_option("--normals", options->normals, "rotate (the paper's (8)) or jacobian (exact)")
      ->capture_default_str();
  deform->add_option("--frame", options->frame,
                     "auto (found from the mesh) or identity (mesh coordinates are the frame)")
      ->check(CLI::IsMember({"auto", "identity"}))
      ->capture_default_str();
  deform->add_flag("--clamp", options->clamp, "Clamp m into its valid range instead of failing");
  deform->add_option("--device", options->device,
                     "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  return [options] { return run_deform(*options); };
}

}  // namespace finflex::cli

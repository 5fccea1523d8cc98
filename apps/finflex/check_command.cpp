// finflex check: the chosen OpenCL device against the double reference on one mesh,
// for both bend modes and both normal modes, m across the whole valid range.
// Prints one row per setting; exit 0 when every row is within the tolerances of
// finflex/accuracy.hpp, 2 otherwise. The mesh's normals are recomputed from its faces
// first, so the face-angle column shows only what the deformation does to them.
#include <cstdio>
#include <memory>
#include <string>

#include "finflex/cli_errors.hpp"
#include "finflex/commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct CheckOptions {
  std::string in;
  std::string device;
};

// m at fractions of the limit, both signs, the limit itself included.
std::vector<float> parameter_sweep(double x_max) {
  std::vector<float> m;
  for (double fraction : {0.0, 0.1, -0.35, 0.6, -0.85, 1.0, -1.0}) {
    m.push_back(static_cast<float>(fraction * max_abs_m(x_max)));
  }
  return checked_bend_params(m, x_max, /*clamp=*/true);
}

int run_check(const CheckOptions& options) {
  try {
    Mesh rest = load_mesh(options.in);
    compute_vertex_normals(rest);
    const LocalMesh local = make_local_mesh(rest, find_body_frame(rest));
    const std::vector<float> m = parameter_sweep(local.x_max);
    Context context(options.device);
    ClDeformer deformer(context, local);
    const ReferenceDeformer reference(local);
    DeviceBatch batch = deformer.allocate(m.size());

    std::printf("device: %s\nmesh: %s (%zu vertices), s_x %.6g, x_max %.4f, m in [%.4f, %.4f]\n",
                context.description().device_name.c_str(), options.in.c_str(), local.vertex_count(),
                local.frame.length, local.x_max, -max_abs_m(local.x_max), max_abs_m(local.x_max));
    std::printf("%-6s %-9s %14s %14s %10s %12s %s\n", "mode", "normals", "position/s_x", "normal",
                "skipped", "face angle", "verdict");
    bool all_within = true;
    for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
      for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
        const BendSettings settings{mode, normals};
        deformer.enqueue(m, settings, batch);
        const DeformedBatch<float> device = deformer.read(batch);
        const AccuracyReport report =
            compare_to_reference(local, m, settings, device, reference.run(m, settings));
        // Face agreement of the instance at 0.6 of the limit (index 3 of the sweep).
        const double face_angle = mean_angle_to_face_normals(instance_mesh(rest, device, 3));
        all_within = all_within && report.within_tolerance();
        std::printf("%-6s %-9s %14.3g %14.3g %10zu %10.4f deg %s\n", to_string(mode),
                    to_string(normals), report.max_position_error / local.frame.length,
                    report.max_normal_error, report.skipped_normals, face_angle * 57.29577951308232,
                    report.within_tolerance() ? "ok" : "OUT OF TOLERANCE");
      }
    }
    if (!all_within) return fail("check", "the device is out of tolerance against the reference");
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("check", error.what());
  }
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* check =
      app.add_subcommand("check", "Compare an OpenCL device with the double reference on a mesh");
  check->add_option("--in", options->in, "Mesh to check with")->required();
  check->add_option("--device", options->device,
                    "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  return [options] { return run_check(*options); };
}

}  // namespace finflex::cli

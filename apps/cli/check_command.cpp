// finflex check: the chosen OpenCL device against the double reference on one mesh:
// the whole-body bend in both modes, or a rig (--rig), with both normal modes and
// every parameter across its whole valid range. Prints one row per setting; exit 0
// when every row is within the tolerances of finflex/accuracy.hpp, 2 otherwise. The
// mesh's normals are recomputed from its faces first, so the face-angle column shows
// only what the deformation does to them. With --levels N (a rig), each of the mesh's
// first N levels of detail is checked too (finflex/detail_levels.hpp), one row each.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli_errors.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"
#include "level_flags.hpp"

namespace finflex::cli {
namespace {

struct CheckOptions {
  std::string in;
  std::string rig;
  std::string device;
  std::string levels = "1";
  std::string triangle_ratio = "0.25";
  bool freeze_fins = true;
};

// Instance k: every parameter at a fraction of its limit (0, 0.1, -0.35, 0.6, -0.85
// and the limits themselves), alternate parameters with opposite signs; clamped, so
// the values at the limits are the ones the backends use.
RigParameters parameter_sweep(const Rig& rig) {
  const double fractions[] = {0.0, 0.1, -0.35, 0.6, -0.85, 1.0, -1.0};
  RigParameters values(rig, std::size(fractions));
  for (std::size_t i = 0; i < std::size(fractions); ++i) {
    for (std::size_t p = 0; p < rig.parameters.size(); ++p) {
      const RigParameter& parameter = rig.parameters[p];
      for (std::size_t k = 0; k < parameter.count; ++k) {
        values.values()[i * values.values_per_instance() + parameter.offset + k] =
            static_cast<float>(fractions[i] * parameter.limit * (p % 2 ? -1.0 : 1.0));
      }
    }
  }
  std::vector<float> checked(values.values().size());
  check_parameters(rig, values.view(), /*clamp=*/true, checked.data());
  values.values() = checked;
  return values;
}

// One row: the model with every normal mode; false when out of tolerance.
bool check_model(Context& context, const RiggedMesh& model, const std::string& label) {
  const RigParameters values = parameter_sweep(model.rig());
  const ParameterView view = values.view();
  ClDeformer deformer(context, model);
  DeviceBatch batch = deformer.allocate(view.instance_count);
  bool all_within = true;
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    ClJob job;
    job.instances = view.instance_count;
    job.parameters = view;
    job.normals = normals;
    job.outputs = &batch;
    deformer.enqueue(job);
    const DeformedBatch<float> device = deformer.read(batch);
    DeformedBatch<double> reference;
    ReferenceJob reference_job;
    reference_job.instances = view.instance_count;
    reference_job.parameters = view;
    reference_job.normals = normals;
    reference_job.outputs = &reference;
    run_reference(model, reference_job);
    const AccuracyReport report = compare_to_reference(model, view, normals, device, reference);
    // Face agreement of the instance at 0.6 of the limits (index 3 of the sweep).
    const double face_angle = mean_angle_to_face_normals(instance_mesh(model.mesh(), device, 3));
    const double length = model.rig().components.front().frame.length;
    all_within = all_within && report.within_tolerance();
    std::printf("%-14s %-9s %14.3g %14.3g %10zu %10.4f deg %s\n", label.c_str(), to_string(normals),
                report.max_position_error / length, report.max_normal_error, report.skipped_normals,
                face_angle * 57.29577951308232,
                report.within_tolerance() ? "ok" : "OUT OF TOLERANCE");
  }
  return all_within;
}

void check_check(const CheckOptions& options) {
  check_input_file("--in", options.in, mesh_extensions());
  if (!options.rig.empty()) check_input_file("--rig", options.rig);
  const LevelOptions levels = parse_level_options(options.levels, options.triangle_ratio);
  if (levels.levels > 1 && options.rig.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--levels",
                "--levels " + options.levels + ": levels of detail are checked with a --rig");
  }
}

// After check_check: the device, then the files.
int run_check(const CheckOptions& options) {
  try {
    Context context(options.device);
    Mesh rest = for_option("--in", [&] { return load_mesh(options.in); });
    compute_vertex_normals(rest);
    std::printf("device: %s\nmesh: %s (%zu vertices)\n", context.description().device_name.c_str(),
                options.in.c_str(), rest.vertex_count());
    std::printf("%-14s %-9s %14s %14s %10s %12s %s\n", "deformation", "normals", "position/s_x",
                "normal", "skipped", "face angle", "verdict");
    bool all_within = true;
    if (options.rig.empty()) {
      const BodyFrame frame = find_body_frame(rest);
      for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
        const RiggedMesh model = RiggedMesh::single_bend(rest, frame, mode);
        const double limit = model.rig().parameters[0].limit;
        if (mode == BendMode::kPaper) {
          std::printf("s_x %.6g, x_max %.4f, m in [%.4f, %.4f]\n", frame.length,
                      model.rig().components[0].chain[0].geometry.x_max, -limit, limit);
        }
        all_within =
            check_model(context, model, std::string("bend ") + to_string(mode)) && all_within;
      }
    } else {
      const RiggedMesh model(
          rest, resolve_rig(for_option("--rig", [&] { return load_rig_file(options.rig); }), rest));
      const LevelOptions level_options =
          parse_level_options(options.levels, options.triangle_ratio, options.freeze_fins);
      if (level_options.levels == 1) {
        all_within = check_model(context, model, "rig") && all_within;
      } else {
        const DetailLevels levels = for_option("--levels", [&] {
          return make_detail_levels(model, frozen_fin_bounds(level_options, model));
        });
        for (std::size_t k = 0; k < levels.size(); ++k) {
          all_within =
              check_model(context, levels.level(k).model, "rig level " + std::to_string(k)) &&
              all_within;
        }
        print_levels(levels, model.rig().components.front().frame.length);
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
  check->add_option("--rig", options->rig,
                    "Rig file: check the rig instead of the whole-body bend");
  check->add_option("--device", options->device,
                    "OpenCL device: 'P:D' indices or a name substring (see finflex info)");
  check
      ->add_option("--levels", options->levels,
                   "With --rig: check this many levels of detail, the full mesh included (1-8)")
      ->capture_default_str();
  check
      ->add_option("--triangle-ratio", options->triangle_ratio,
                   "Each level's triangles as a fraction of the finer level's")
      ->capture_default_str();
  check->add_flag(kFreezeFinsFlag, options->freeze_fins, kFreezeFinsHelp);
  return {[options] { check_check(*options); }, [options] { return run_check(*options); }};
}

}  // namespace finflex::cli

// finflex subdivide: Loop-subdivide a triangle mesh (e.g. the bundled control cage
// into a 100k-vertex fish for benchmarks).
#include <cstdio>
#include <memory>
#include <string>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct SubdivideOptions {
  std::string in;
  std::string out;
  int levels = 1;
};

int run_subdivide(const SubdivideOptions& options) {
  try {
    const Mesh dense = subdivide_loop(load_mesh(options.in), options.levels);
    save_mesh(options.out, dense);
    std::printf("%zu vertices, %zu triangles -> %s\n", dense.vertex_count(), dense.triangle_count(),
                options.out.c_str());
    return kExitSuccess;
  } catch (const std::exception& error) {
    return fail("subdivide", error.what());
  }
}

}  // namespace

Command add_subdivide_command(CLI::App& app) {
  auto options = std::make_shared<SubdivideOptions>();
  CLI::App* command = app.add_subcommand("subdivide", "Loop-subdivide a triangle mesh");
  command->add_option("--in", options->in, "Input mesh")->required();
  command->add_option("--out", options->out, "Output mesh")->required();
  command->add_option("--levels", options->levels, "Subdivision levels (0-8)")
      ->capture_default_str();
  return [options] { return run_subdivide(*options); };
}

}  // namespace finflex::cli

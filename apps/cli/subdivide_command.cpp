// finflex subdivide: Loop-subdivide a triangle mesh (e.g. the bundled control cage
// into a 100k-vertex fish for benchmarks).
#include <cstdio>
#include <memory>
#include <string>

#include "cli_errors.hpp"
#include "cli_numbers.hpp"
#include "cli_paths.hpp"
#include "commands.hpp"
#include "finflex/finflex.hpp"

namespace finflex::cli {
namespace {

struct SubdivideOptions {
  std::string in;
  std::string out;
  std::string levels = "1";
};

int check_subdivide(const SubdivideOptions& options) {
  const std::size_t levels =
      parse_count(options.levels, "--levels", 0, 8, "each level makes four times the triangles");
  check_input_file("--in", options.in, mesh_extensions());
  check_output_file("--out", options.out, mesh_extensions());
  return static_cast<int>(levels);
}

int run_subdivide(const SubdivideOptions& options) {
  try {
    const int levels = check_subdivide(options);
    const Mesh dense =
        subdivide_loop(for_option("--in", [&] { return load_mesh(options.in); }), levels);
    for_option("--out", [&] { save_mesh(options.out, dense); });
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
  command->add_option("--levels", options->levels, "Subdivision levels (0 to 8)")
      ->capture_default_str();
  return {[options] { check_subdivide(*options); }, [options] { return run_subdivide(*options); }};
}

}  // namespace finflex::cli

// The C++ side of bench/python_overhead.py: ClDeformer::enqueue of one frame (the
// parameters of N instances in, an event out) timed around the call with the device
// idle, over F frames, on the bundled Blub with the paper bend and rotate normals, as
// the Python script does it. Prints one JSON object (median and mean, microseconds).
//
//   bench_host_overhead [FRAMES=400] [INSTANCES=4000] [DEVICE] [MESH=data/blub/fish.obj]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include <finflex/finflex.hpp>

int main(int argc, char** argv) {
  const std::size_t frames = argc > 1 ? std::stoul(argv[1]) : 400;
  const std::size_t instances = argc > 2 ? std::stoul(argv[2]) : 4000;
  const std::string device = argc > 3 ? argv[3] : "";
  const std::string mesh_path = argc > 4 ? argv[4] : FINFLEX_DATA_DIR "/blub/fish.obj";
  try {
    const finflex::Mesh mesh = finflex::load_mesh(mesh_path);
    const finflex::RiggedMesh model = finflex::RiggedMesh::single_bend(
        mesh, finflex::find_body_frame(mesh), finflex::BendMode::kPaper);
    finflex::Context context(device);
    finflex::ClDeformer deformer(context, model);
    finflex::DeviceBatch batch = deformer.allocate(instances);
    finflex::RigParameters m(model, instances);
    std::fill(m.values().begin(), m.values().end(), 0.1f);
    finflex::ClJob job;
    job.instances = m.instance_count();
    job.parameters = m.view();
    job.outputs = &batch;
    finflex::check_cl(deformer.enqueue(job).wait(), "clWaitForEvents");

    std::vector<double> seconds;
    for (std::size_t f = 0; f < frames; ++f) {
      const auto start = std::chrono::steady_clock::now();
      const cl::Event done = deformer.enqueue(job);
      seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      finflex::check_cl(done.wait(), "clWaitForEvents");
    }
    const double mean =
        std::accumulate(seconds.begin(), seconds.end(), 0.0) / static_cast<double>(seconds.size());
    std::sort(seconds.begin(), seconds.end());
    const std::size_t n = seconds.size();
    const double median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
    std::printf("{\"frames\": %zu, \"instances\": %zu, \"median_us\": %.3f, \"mean_us\": %.3f}\n",
                frames, instances, median * 1e6, mean * 1e6);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_host_overhead: %s\n", e.what());
    return 1;
  }
}

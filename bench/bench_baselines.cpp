// Baselines measured in the same run as the kernels:
//  - what a user would write without FinFlex: the paper's bend, (7), (8) and the way
//    back to mesh coordinates as a plain C++ loop over float3 arrays (array of
//    structures), OpenMP over instances, compiled -O3 -march=native;
//  - the double-precision CPU reference (the tests' oracle).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

struct Float3 {
  float x, y, z;
};

struct Baseline {
  std::vector<Float3> positions, normals;  // rest, in the body frame
  Float3 origin, axis_x, axis_y, axis_z;   // the way back; axes scaled by s_x for points
  float length;
  double x_max;

  static Baseline& get() {
    static Baseline baseline = [] {
      const Setup& setup = Setup::get();
      const BodyFrame& f = setup.frame;
      Baseline b;
      b.x_max = 0.0;
      for (std::size_t v = 0; v < setup.mesh.vertex_count(); ++v) {
        const glm::dvec3 p = f.point_to_local(glm::dvec3(setup.mesh.positions[v]));
        const glm::dvec3 n = glm::normalize(f.vector_to_local(glm::dvec3(setup.mesh.normals[v])));
        b.positions.push_back({float(p.x), float(p.y), float(p.z)});
        b.normals.push_back({float(n.x), float(n.y), float(n.z)});
        b.x_max = std::max(b.x_max, std::fabs(p.x));
      }
      b.origin = {float(f.origin.x), float(f.origin.y), float(f.origin.z)};
      b.axis_x = {float(f.axis_x.x), float(f.axis_x.y), float(f.axis_x.z)};
      b.axis_y = {float(f.axis_y.x), float(f.axis_y.y), float(f.axis_y.z)};
      b.axis_z = {float(f.axis_z.x), float(f.axis_z.y), float(f.axis_z.z)};
      b.length = float(f.length);
      return b;
    }();
    return baseline;
  }
};

inline Float3 to_mesh(const Baseline& b, float x, float y, float z, float scale, bool offset) {
  const float sx = x * scale, sy = y * scale, sz = z * scale;
  Float3 out{sx * b.axis_x.x + sy * b.axis_y.x + sz * b.axis_z.x,
             sx * b.axis_x.y + sy * b.axis_y.y + sz * b.axis_z.y,
             sx * b.axis_x.z + sy * b.axis_y.z + sz * b.axis_z.z};
  if (offset) {
    out.x += b.origin.x;
    out.y += b.origin.y;
    out.z += b.origin.z;
  }
  return out;
}

// The paper's bend of every vertex of every instance: (15)-(17), (7), (8).
void bend_all(const Baseline& b, const std::vector<float>& m, std::vector<Float3>& out_positions,
              std::vector<Float3>& out_normals) {
  const long instances = static_cast<long>(m.size());
  const std::size_t vertices = b.positions.size();
#pragma omp parallel for schedule(static)
  for (long i = 0; i < instances; ++i) {
    const float mi = m[static_cast<std::size_t>(i)];
    Float3* positions = &out_positions[static_cast<std::size_t>(i) * vertices];
    Float3* normals = &out_normals[static_cast<std::size_t>(i) * vertices];
    for (std::size_t v = 0; v < vertices; ++v) {
      const Float3 p = b.positions[v], n = b.normals[v];
      const float u = 2.0f * mi * p.x, u2 = u * u;
      const float a = 1.0f - u2 * (0.5f + 0.125f * u2);
      const float g = std::sqrt(a * a + u2);
      const float sin_t = u / g, cos_t = a / g;
      const float bent_x = p.x * (1.0f - u2 * (1.0f / 6.0f + u2 / 40.0f));
      const float bent_z = mi * p.x * p.x;
      positions[v] = to_mesh(b, bent_x - p.z * sin_t, p.y, bent_z + p.z * cos_t, b.length, true);
      normals[v] =
          to_mesh(b, cos_t * n.x - sin_t * n.z, n.y, sin_t * n.x + cos_t * n.z, 1.0f, false);
    }
  }
}

}  // namespace

void BM_OpenMPBaseline(benchmark::State& state) {
  const Baseline& b = Baseline::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  const std::vector<float> m = baseline_bend_values(instances, b.x_max);
  std::vector<Float3> positions(instances * b.positions.size()), normals(positions.size());
  // The first frame warms up: pages touched, threads started.
  const double total = time_iterations(
      state, [&] { return host_seconds([&] { bend_all(b, m, positions, normals); }); });
  benchmark::DoNotOptimize(positions.data());
  set_baseline_counters(state, instances, total);
}

void BM_DoubleReference(benchmark::State& state) {
  DeviceModel& bend = Setup::get().bend(BendMode::kPaper);
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  RigParameters m(bend.model, instances);
  m.values() =
      baseline_bend_values(instances, bend.model.rig().components[0].chain[0].geometry.x_max);
  double total = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const DeformedBatch<double> out = run_reference(bend.model, m, NormalMode::kRotate);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(out.positions.data());
    state.SetIterationTime(seconds);
    total += seconds;
  }
  set_baseline_counters(state, instances, total);
}

}  // namespace finflex::bench

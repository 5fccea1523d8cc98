// The OpenMP baseline a careful user would write for the CPU's vector units, measured
// in the same run as the kernels: the paper's bend (15)-(17), (7), (8) and the way back
// to mesh coordinates over structure-of-arrays planes (the layout FinFlex writes,
// finflex/batch.hpp), the vertex loop `#pragma omp simd` over restrict pointers, the
// division by |df/dx| done once as a multiplication by its inverse, OpenMP threads over
// instances. Compiled -O3 -march=native -fno-math-errno (bench/CMakeLists.txt): with
// errno, GCC keeps a branch around each sqrt and vectorises nothing.
#include <cmath>
#include <vector>

#include "bench_support.hpp"

namespace finflex::bench {
namespace {

// The rest mesh in the body frame as six planes (x, y, z of positions, then of
// normals), padded like FinFlex's, and the way back to mesh coordinates:
// origin + s (x e_x + y e_y + z e_z) for points, x e_x + y e_y + z e_z for normals.
struct RestPlanes {
  std::size_t vertices = 0;
  std::size_t stride = 0;
  std::vector<float> planes;
  float s = 1.0f;
  float origin[3] = {}, e_x[3] = {}, e_y[3] = {}, e_z[3] = {};
  double x_max = 0.0;

  static const RestPlanes& get() {
    static const RestPlanes rest = [] {
      const Setup& setup = Setup::get();
      const BodyFrame& f = setup.frame;
      RestPlanes r;
      r.vertices = setup.mesh.vertex_count();
      r.stride = padded_plane_stride(r.vertices);
      r.planes.assign(6 * r.stride, 0.0f);
      for (std::size_t v = 0; v < r.vertices; ++v) {
        const glm::dvec3 p = f.point_to_local(glm::dvec3(setup.mesh.positions[v]));
        const glm::dvec3 n = glm::normalize(f.vector_to_local(glm::dvec3(setup.mesh.normals[v])));
        for (int c = 0; c < 3; ++c) {
          r.planes[std::size_t(c) * r.stride + v] = float(p[c]);
          r.planes[std::size_t(c + 3) * r.stride + v] = float(n[c]);
        }
        r.x_max = std::max(r.x_max, std::fabs(p.x));
      }
      r.s = float(f.length);
      for (int c = 0; c < 3; ++c) {
        r.origin[c] = float(f.origin[c]);
        r.e_x[c] = float(f.axis_x[c]);
        r.e_y[c] = float(f.axis_y[c]);
        r.e_z[c] = float(f.axis_z[c]);
      }
      return r;
    }();
    return rest;
  }
};

// Every vertex of every instance into planes: component c of instance i at
// [(i * 3 + c) * stride + v].
void bend_all_simd(const RestPlanes& r, const std::vector<float>& m, float* out_positions,
                   float* out_normals) {
  const long instances = static_cast<long>(m.size());
  const std::size_t vertices = r.vertices, stride = r.stride;
  const float* __restrict rx = r.planes.data();
  const float* __restrict ry = rx + stride;
  const float* __restrict rz = ry + stride;
  const float* __restrict nx = rz + stride;
  const float* __restrict ny = nx + stride;
  const float* __restrict nz = ny + stride;
  const float s = r.s;
  const float ox = r.origin[0], oy = r.origin[1], oz = r.origin[2];
  const float ax = r.e_x[0], ay = r.e_x[1], az = r.e_x[2];
  const float bx = r.e_y[0], by = r.e_y[1], bz = r.e_y[2];
  const float cx = r.e_z[0], cy = r.e_z[1], cz = r.e_z[2];
#pragma omp parallel for schedule(static)
  for (long i = 0; i < instances; ++i) {
    const float mi = m[static_cast<std::size_t>(i)];
    const std::size_t first = static_cast<std::size_t>(i) * 3 * stride;
    float* __restrict px = out_positions + first;
    float* __restrict py = px + stride;
    float* __restrict pz = py + stride;
    float* __restrict qx = out_normals + first;
    float* __restrict qy = qx + stride;
    float* __restrict qz = qy + stride;
#pragma omp simd
    for (std::size_t v = 0; v < vertices; ++v) {
      const float x = rx[v], y = ry[v], z = rz[v];
      // (15)-(17) with u = 2 m x: x' = x (1 - u^2/6 - u^4/40), z' = m x^2,
      // n = (-u, 0, a) / |(a, u)|, a = 1 - u^2/2 - u^4/8.
      const float u = 2.0f * mi * x, u2 = u * u;
      const float a = 1.0f - u2 * (0.5f + 0.125f * u2);
      const float inverse_g = 1.0f / std::sqrt(a * a + u2);
      const float sin_t = u * inverse_g, cos_t = a * inverse_g;
      const float bent_x = x * (1.0f - u2 * (1.0f / 6.0f + u2 * (1.0f / 40.0f)));
      const float bent_z = 0.5f * u * x;
      // (7), then back to mesh coordinates.
      const float lx = s * (bent_x - z * sin_t), ly = s * y, lz = s * (bent_z + z * cos_t);
      px[v] = ox + lx * ax + ly * bx + lz * cx;
      py[v] = oy + lx * ay + ly * by + lz * cy;
      pz[v] = oz + lx * az + ly * bz + lz * cz;
      // (8): the rotation about e_y taking e_z to n.
      const float mx = cos_t * nx[v] - sin_t * nz[v], my = ny[v];
      const float mz = sin_t * nx[v] + cos_t * nz[v];
      qx[v] = mx * ax + my * bx + mz * cx;
      qy[v] = mx * ay + my * by + mz * cy;
      qz[v] = mx * az + my * bz + mz * cz;
    }
  }
}

}  // namespace

void BM_OpenMPSimdBaseline(benchmark::State& state) {
  const RestPlanes& rest = RestPlanes::get();
  const std::size_t instances = static_cast<std::size_t>(state.range(0));
  const std::vector<float> m = baseline_bend_values(instances, rest.x_max);
  std::vector<float> positions(instances * 3 * rest.stride), normals(positions.size());
  // The first frame warms up: pages touched, threads started.
  const double total = time_iterations(state, [&] {
    return host_seconds([&] { bend_all_simd(rest, m, positions.data(), normals.data()); });
  });
  benchmark::DoNotOptimize(positions.data());
  set_baseline_counters(state, instances, total);
}

}  // namespace finflex::bench

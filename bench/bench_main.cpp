// FinFlex throughput benchmarks on the default OpenCL device (or FINFLEX_DEVICE):
// the single bend and a rigged fish (fused and multi-pass), next to a write-only
// kernel and a copy kernel of the same NDRange and output planes, measured in the
// same run. Times are the kernels' own, from OpenCL profiling events, after a warm-up
// launch of every kernel shape.
//
//   build/bench/bench_deform --benchmark_counters_tabular=true
//   FINFLEX_MESH=mesh.obj FINFLEX_RIG=mesh.rig.json FINFLEX_DEVICE=H100 build/bench/bench_deform
//
// Counters: vertices/s (deformed vertices, all instances), bytes/s (bytes written:
// 24 per vertex, positions + normals in float32), write_fraction (bytes/s over the
// write-only kernel's, this run), and for rigs passes and bytes/vertex moved.
// Baselines: the same bend as a plain OpenMP C++ loop over float3 arrays, and as the
// loop a careful user would write (planes, `#pragma omp simd`), both -O3 with the
// machine's instructions (FINFLEX_BASELINE_ARCH); the double-precision reference.
#include "bench_support.hpp"

namespace finflex::bench {
namespace {

void instance_counts(benchmark::internal::Benchmark* b) {
  for (int n : {1, 10, 100, 1000, 4000}) b->Arg(n);
  b->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
}

// Registered in this order: the write-only kernel first, so the others can compare.
// The device's instances per work-item, and 4 (the rig kernels' on GPUs), with one
// lane; the device's lanes (vector stores: CPUs) with streaming and with plain stores;
// the fastest is the reference. `uniform`: one value everywhere, for comparison only
// (GPUs may compress it).
BENCHMARK_CAPTURE(BM_WriteOnly, float32, NormalFormat::kFloat32, 0, WriteValues::kDeviceDefault, 1,
                  false)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, float32_4_per_item, NormalFormat::kFloat32, 4,
                  WriteValues::kDeviceDefault, 1, false)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, float32_lanes, NormalFormat::kFloat32, 0,
                  WriteValues::kDeviceDefault, 0, true)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, float32_lanes_plain, NormalFormat::kFloat32, 0,
                  WriteValues::kDeviceDefault, 0, false)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, float32_uniform, NormalFormat::kFloat32, 0, WriteValues::kConstant,
                  1, false)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, half, NormalFormat::kHalf, 0, WriteValues::kDeviceDefault, 1, false)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_WriteOnly, half_4_per_item, NormalFormat::kHalf, 4,
                  WriteValues::kDeviceDefault, 1, false)
    ->Apply(instance_counts);
BENCHMARK(BM_CopyRest)->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, paper_rotate, BendMode::kPaper, NormalMode::kRotate,
                  NormalFormat::kFloat32)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, exact_rotate, BendMode::kExact, NormalMode::kRotate,
                  NormalFormat::kFloat32)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, paper_jacobian, BendMode::kPaper, NormalMode::kJacobian,
                  NormalFormat::kFloat32)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, exact_jacobian, BendMode::kExact, NormalMode::kJacobian,
                  NormalFormat::kFloat32)
    ->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Bend, paper_rotate_half, BendMode::kPaper, NormalMode::kRotate,
                  NormalFormat::kHalf)
    ->Apply(instance_counts);
BENCHMARK(BM_OpenMPBaseline)->Apply(instance_counts);
BENCHMARK(BM_OpenMPSimdBaseline)->Apply(instance_counts);
BENCHMARK(BM_HostOverhead)->Arg(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DoubleReference)
    ->Arg(1)
    ->Arg(10)
    ->Arg(100)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rig, fused, RigPath::kFused)->Apply(instance_counts);
BENCHMARK_CAPTURE(BM_Rig, passes, RigPath::kPasses)->Apply(instance_counts);

}  // namespace
}  // namespace finflex::bench

BENCHMARK_MAIN();

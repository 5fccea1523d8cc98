// Frames of a batch on one device, timed by OpenCL profiling events, next to a
// write-only kernel of the same outputs (the device's write bandwidth, measured in the
// same run: the fastest of its shapes; on CPUs that shape also runs after every frame,
// write_fraction_interleaved the median of the frames' own ratios), and the record of
// a run as `finflex bench --json` prints it (docs/benchmarks.md's counters).
//
// On GPUs the frames run ahead (the next one enqueued before this one is waited for,
// "frames_ahead": true), as in an application's frame loop; on CPUs one by one.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_layouts.hpp"
#include "deformer_report.hpp"
#include "finflex/finflex.hpp"
#include "finflex/internal/cl_tuning.hpp"
#include "timing.hpp"

namespace finflex::bench {

// What a run deforms, how, and into what.
struct FrameBenchSettings {
  std::size_t instances = 1000;
  std::size_t frames = 100;
  NormalMode normals = NormalMode::kRotate;
  NormalFormat format = NormalFormat::kFloat32;
  RigPath path = RigPath::kAuto;
  ClTuning options;  // the backend's choices, for experiments
  OutputsChoice outputs;
  // The swim (swim_bench.hpp): the tank's steps recorded before the timed frames
  // (true), or stepped inside the frame loop.
  bool recorded_swim_inputs = true;
};

// The write-only kernel's fastest shape for a batch, and its median frame time.
struct WriteOnlyShape {
  std::size_t per_item = 1;
  std::size_t lanes = 1;
  bool streaming = false;
  double seconds = 0.0;
};

// What a benchmark measured, with the write-only kernel it is compared with.
struct Measured {
  std::string what;  // "bend paper", "rig fused", "swim passes", ...
  bool swim = false;
  PassReport passes;
  FrameTimes times;
  const DeviceBatch* batch = nullptr;
  KernelShape shape;                 // the deformer's for the batch
  std::size_t vertices = 0;          // per instance
  std::size_t output_vertices = 0;   // the outputs' (slots or mesh vertices)
  std::size_t bytes_per_vertex = 0;  // written per output vertex and instance
  // Outputs in host memory: the map that hands each frame to the host
  // (ClDeformer::map_host) after the kernels completed, host wall time per frame.
  std::vector<double> host_map_seconds;
  // The swim: of the host's enqueue, the driver's part (inputs checked, copied,
  // uploaded, the driver kernel launched).
  std::vector<double> host_driver_seconds;
  // The write-only kernel's fastest shape, timed on its own before the frames; on CPUs
  // also after every frame (times.reference).
  WriteOnlyShape write_only;
};

// Frames run ahead (time_frames) on GPUs: the host enqueues the next frame while the
// device runs this one, as an application's frame loop does; on CPUs each frame is
// waited for (the host's work would take the kernels' cores).
bool frames_ahead(Context& context);

// The write-only kernel through the batch's layout: the fastest of the deformer's
// instances per work-item and 4 (the rig kernels' on GPUs), each with one lane and,
// when the deformer has more for this batch (FinFlex's float32 planes), with its lanes
// (vector stores, kernels/cpu/lane_outputs.cl), streaming and plain.
WriteOnlyShape fastest_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                                  const KernelShape& deformer, std::size_t frames);

// On CPUs, whose frames are waited for one by one, the write-only kernel's fastest
// shape runs after every frame too (time_frames' reference): on a shared machine a
// frame's time drifts from run to run by a fifth or more, and a frame and the
// write-only kernel right after it see the machine in the same state. None on GPUs
// (frames ahead).
std::function<cl::Event()> write_reference(Context& context, DeviceBatch& batch,
                                           std::size_t vertices, const WriteOnlyShape& shape);

// Every parameter of every instance set to value(instance, parameter, k) for the k-th
// of the parameter's values (a table's entries; 0 for a single value).
void set_parameters(RigParameters& values,
                    const std::function<float(std::size_t, std::size_t, std::size_t)>& value);

// The parameters of frame f: single values swing through half their range in a
// travelling phase, tables (a spine's angles) carry a smooth travelling wave of 0.3
// rad, far from folding.
void animate_parameters(RigParameters& values, std::size_t frame);

// A job writing `values` into `batch`.
ClJob frame_job(const RigParameters& values, DeviceBatch& batch, NormalMode normals,
                RigPath path = RigPath::kAuto);

// What a deformation bench keeps alive while its result is read: the deformer, the
// outputs and their host memory.
struct DeformBench {
  std::unique_ptr<ClDeformer> deformer;
  HostMemory host;
  DeviceBatch batch;
};

// The whole-body bend (`bend`: its mode's name, as the record says it) or a rig (`bend`
// empty), its parameters animated on the host (animate_parameters). ClDeformer's
// errors come out as it throws them (e.g. "tuning.lanes").
Measured measure_deform(Context& context, const RiggedMesh& model, const std::string& bend,
                        const FrameBenchSettings& settings, DeformBench& bench);

// The run's record, its keys in this order: device, mesh (`mesh`, as given), deformation,
// normals, normal_format, layout, order, previous_positions, vertices, instances,
// frames, passes, the frame times and rates, moved_bytes_per_vertex, the write-only
// kernel's bandwidth and fractions, the host's times (the swim's driver and its inputs;
// the host map), kernel_seconds_median, the kernel shape, frames_ahead and the host's
// huge pages (huge_page_settings.hpp).
nlohmann::ordered_json frame_bench_record(Context& context, const std::string& mesh,
                                          const FrameBenchSettings& settings,
                                          const Measured& measured);

}  // namespace finflex::bench

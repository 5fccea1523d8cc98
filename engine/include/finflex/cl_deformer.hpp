// The OpenCL backend: a model (finflex/model.hpp) uploaded once to a device, and jobs
// (finflex/job.hpp) enqueued on the context's in-order queue, each instance with its
// own parameters, one NDRange over (vertex slots x instances) per launch.
//
//   Context context;                                   // PoCL on the CPU, or a GPU
//   ClDeformer deformer(context, fish);                // uploads the rest mesh once
//   DeviceBatch batch = deformer.allocate(4000);       // once
//   RigParameters values(fish, 4000);
//   ClJob job;
//   job.instances = 4000;
//   job.parameters = values.view();
//   job.outputs = &batch;
//   for each frame:
//     ... fill values ...
//     cl::Event done = deformer.enqueue(job);
//     ... hand batch.positions / batch.normals (cl::Buffer) to the renderer, or read()
//
// Asynchronous: enqueue() returns after enqueueing a non-blocking parameter upload
// and the kernels; it waits on the host only when the parameter staging buffer it
// reuses (one of three, in turn) still belongs to a frame in flight. Nothing calls
// clFinish.
//
// How a model runs: vertices are reordered into slots so that every component is a
// contiguous range of whole work-groups (slot_of_vertex(); remapped_indices() are
// the mesh's triangles over slots: draw the outputs with them). The whole-body bend
// (RiggedMesh::is_single_bend) has its own kernel; other rigs run fused (one kernel,
// each vertex's whole path in registers) or in passes (job.path).
//
// Thread-safety:
// - Deformers on one Context may be used from different threads at once.
// - One deformer may be shared by several threads: enqueue() holds the deformer's
//   lock from its checks to its last launch (its staging ring, parameter buffer,
//   scratch sets and kernel arguments are per frame), so each thread's frames come
//   out whole and right. The cost: one uncontended lock per frame (about 25 ns,
//   against tens of microseconds for the frame's enqueue); threads sharing a deformer
//   take turns to enqueue (the kernels still run on the device's one in-order queue),
//   and each frame on another batch than the deformer's last sets the kernel
//   arguments again. check(), read(), allocate(), layout() and the accessors only
//   read what is fixed at construction.
// - A DeviceBatch, its RigParameters and a ClJob belong to one thread at a time; two
//   threads enqueueing into one batch get whichever frame the queue runs last.
// - A RigFrame belongs to one thread at a time; RigFrames on several threads may share
//   deformers.
// - read() blocks until every command queued on the context before it is done (all
//   threads' frames, not only this batch's).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/context.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/export.hpp"
#include "finflex/job.hpp"
#include "finflex/model.hpp"
#include "finflex/parameters.hpp"

namespace finflex {

// A frame's inputs already on the device, written by a kernel of the caller's (a swim
// driver, finflex/cl_swim.hpp) and used instead of uploading the job's host values.
struct ClDeviceInputs {
  // Instead of job.parameters: rows of values_per_instance() floats, packed. The values
  // are the writer's to keep in range: nothing checks them on the host.
  const cl::Buffer* parameters = nullptr;
  // Instead of job.placements: kPlacementFloats per instance.
  const cl::Buffer* placements = nullptr;
  // The rig's derived values of this frame (DeformerType::derived_count: a spine's
  // running integrals), written by the kernel that wrote `parameters`
  // (ClSwimDriver::derived_buffer()), derived_floats_per_instance() floats per
  // instance: the frame skips rig_prepare. Null: rig_prepare computes them.
  const cl::Buffer* derived = nullptr;
};

// The instances a frame deforms, named by a list on the device (a level's list of a
// LevelChooser, finflex/level_choice.hpp, or the caller's): output row i holds the
// instance entries[first + i], read from the frame's device inputs (its values, derived
// values and placement at that index). The list's length is read on the device,
// counts[count_index], and never exceeds the job's instances (the outputs' rows), so
// the host never waits for it: the kernels are launched for the outputs' rows, at most
// a device's worth of work-items, and stride over the list; rows past the length are
// left as they were. Entries at or past `sources` are skipped (their rows left too).
struct ClInstanceList {
  const cl::Buffer* entries = nullptr;  // cl_uint instance indices; null: no list
  std::size_t first = 0;                // the list's first entry in `entries`
  const cl::Buffer* counts = nullptr;   // cl_uint; the list's length at counts[count_index]
  std::size_t count_index = 0;
  std::size_t sources = 0;  // the instances the inputs hold (> 0)
};

// A frame of a ClDeformer: the job of finflex/job.hpp, written into a DeviceBatch, and
// what only the device has.
struct ClJob : BasicDeformJob<DeviceBatch> {
  RigPath path = RigPath::kAuto;
  // Inputs on the device instead of the host's (each null: the host's).
  ClDeviceInputs device;
  // Only the listed instances (entries null: instances 0 .. instances - 1). A listed
  // job reads its values from device.parameters (sources rows) and its placements, if
  // any, from device.placements: kInvalidArgument naming "job.list..." otherwise, or
  // for buffers too small for first + instances entries or count_index.
  ClInstanceList list;
  // Work the job's first command waits for; none when null.
  const std::vector<cl::Event>* wait = nullptr;
};

// The backend's tuning knobs and what a deformer chose: finflex/internal/cl_tuning.hpp
// (benchmarks and tests; the defaults are the measured choices).
struct ClTuning;
namespace internal {
struct DeformerAccess;
}

class FINFLEX_API ClDeformer {
 public:
  // Uploads the model: rest mesh planes over slots (each vertex in its first stage's
  // frame), the stage table and the rig's dispatch code. kInvalidMesh when the mesh
  // has more than 2^32 slots.
  ClDeformer(Context& context, const RiggedMesh& model);
  ClDeformer(Context& context, const RiggedMesh& model, const ClTuning& tuning);
  ~ClDeformer();
  ClDeformer(const ClDeformer&) = delete;
  ClDeformer& operator=(const ClDeformer&) = delete;

  const RiggedMesh& model() const;
  Context& context() const;

  // FinFlex's planes for `instances` instances, normals and tangents (where the mesh
  // has them) in `format`: allocate's layout, and the one to start another from.
  OutputLayout layout(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;
  // Allocates the outputs of `instances` instances in FinFlex's planes, normals and
  // tangents in `format`. kInvalidArgument for 0, kOutOfRange naming "instances" when
  // one attribute array would exceed the device's largest allocation or above
  // kMaxDeviceInstances. On a CPU device an attribute's buffer of 2 MiB or more is host
  // memory aligned to 2 MiB and advised as transparent huge pages (Linux), wrapped
  // with CL_MEM_USE_HOST_PTR (docs/benchmarks.md#choice-huge-page-outputs); for
  // bind_host, align and advise your own memory alike for the same gain.
  DeviceBatch allocate(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;

  // ---- Hand-off (finflex/output_layout.hpp, docs/handoff.md) ----
  // The vertices an output layout in `order` covers: the slots (slot_of_vertex(),
  // padding included) or the mesh's vertices.
  std::size_t output_vertices(VertexOrder order) const;
  // Outputs in any layout: allocated by the deformer (a buffer per attribute), in the
  // caller's buffers, or in the caller's host memory. Every descriptor and buffer is
  // checked (validate_output_layout, sizes against OutputLayout::required_bytes):
  // kInvalidArgument naming the attribute ("outputs.normals.vertex_stride", ...).
  DeviceBatch allocate(std::size_t instances, const OutputLayout& outputs) const;
  DeviceBatch bind(std::size_t instances, const OutputLayout& outputs,
                   const OutputBuffers& buffers) const;
  DeviceBatch bind_host(std::size_t instances, const OutputLayout& outputs,
                        const HostOutputs& host) const;
  // A bind_host batch's frame in the caller's memory: maps its buffers for the host,
  // blocking until the frame is there (on CPU devices the kernels wrote it there
  // already: no copy). The next enqueue() on the batch unmaps them; so does unmap_host.
  void map_host(DeviceBatch& batch);
  void unmap_host(DeviceBatch& batch);

  // Validates the job against this deformer's model (ClJob::validate, then: its
  // outputs were made by this deformer for job.instances instances: "job.outputs"
  // names what does not fit), checks its parameters (check_parameters)
  // into the next staging buffer, uploads them without blocking after job.wait, and
  // enqueues the kernels. Returns the last kernel's event. `kernel_events`, when given,
  // receives the event of every kernel launched, in order (profiling): rig_prepare when
  // the rig has derived values, then the deformation's.
  cl::Event enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events = nullptr);
  // Throws what enqueue() would throw for `job`, and enqueues nothing.
  void check(const ClJob& job) const;

  // Blocking read of a batch in any layout, decoded to float; the result's accessors
  // take mesh vertex indices.
  DeformedBatch<float> read(const DeviceBatch& batch);

  const std::vector<std::uint32_t>& slot_of_vertex() const;
  const std::vector<std::uint32_t>& remapped_indices() const;
  // True when enqueue() runs the single-bend kernel (RiggedMesh::is_single_bend, unless
  // the deformer's tuning asks for the rig kernels).
  bool uses_single_bend_kernel() const;
  // Derived values per instance (a spine's running integrals; 0 when the rig has none):
  // the floats a ClJob::device.derived holds for each instance.
  std::size_t derived_floats_per_instance() const;
  // The path RigPath::kAuto resolves to for this model.
  RigPath automatic_path() const;

  // The work-group size along the slots (every plane stride is a multiple of it).
  static constexpr std::size_t kGroupSize = 64;
  // Most stages on one vertex's path that the fused kernel is generated for.
  static constexpr std::size_t kMaxFusedStages = 64;

 private:
  friend class RigFrame;
  friend struct internal::DeformerAccess;
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Several models (e.g. two species) deformed in one frame: each entry is a deformer
// with its own instances, batch and parameters; enqueue() launches them all on the
// context's queue without waiting.
class FINFLEX_API RigFrame {
 public:
  RigFrame();
  ~RigFrame();
  RigFrame(const RigFrame&) = delete;
  RigFrame& operator=(const RigFrame&) = delete;

  // Adds `instances` instances of `deformer`'s model (the deformer must outlive the
  // frame), outputs in `format`; returns the entry's index. Parameters start at the
  // rest pose (zeros).
  std::size_t add(ClDeformer& deformer, std::size_t instances,
                  NormalFormat format = NormalFormat::kFloat32);

  std::size_t size() const;
  RigParameters& parameters(std::size_t entry);
  DeviceBatch& batch(std::size_t entry);

  // One event per entry, in order. Every entry's job is validated and its parameters
  // checked before any is launched: on error nothing is enqueued.
  std::vector<cl::Event> enqueue(NormalMode normals, RigPath path = RigPath::kAuto,
                                 bool clamp = false);

 private:
  struct Entry;
  std::vector<Entry> entries_;
  Entry& at(std::size_t entry);
};

}  // namespace finflex

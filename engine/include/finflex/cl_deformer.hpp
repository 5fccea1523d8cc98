// The OpenCL backend: a model (finflex/model.hpp) uploaded once to a device, and jobs
// (finflex/job.hpp) enqueued on the context's in-order queue, each instance with its
// own parameters, one NDRange over (vertex slots x instances) per launch.
//
//   Context context;                                   // PoCL on the CPU, or a GPU
//   ClDeformer deformer(context, fish);                // uploads the rest mesh once
//   DeviceBatch batch = deformer.allocate(4000);       // once
//   RigParameters values(fish, 4000);
//   ClJob job;
//   job.model = &fish;
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

using ClJob = BasicDeformJob<DeviceBatch, cl::Event, cl::Buffer>;

// How the generated rig kernels tell the work-groups' stages apart (every branch is
// uniform over a work-group).
enum class RigDispatch {
  kAuto,          // kPerComponent on GPUs, kByPathShape on CPUs
  kPerComponent,  // a branch per component, its stages compiled in: fewest instructions
  kByPathShape,   // a kernel per run of components with the same deformers along their
                  // paths, stages read from a table: straight-line kernels, which
                  // PoCL's work-group vectoriser needs; kernels of more than one lane
                  // (vector code already): one kernel, a branch per component
};

// How kernels of more than one lane (ClOptions::lanes) write the outputs.
enum class OutputStores {
  kAuto,       // kStreaming where a frame's outputs are larger than the caches could
               // hold: the device's global memory cache (CL_DEVICE_GLOBAL_MEM_CACHE_SIZE),
               // at most 4 MiB per compute unit (what virtual machines report is not
               // always the host's cache); else kPlain
  kPlain,      // ordinary stores: the outputs pass through the caches (and stay there
               // for whoever reads them next, when they fit)
  kStreaming,  // streaming (non-temporal) stores: whole cache lines to memory, none read
               // first, which halves the memory traffic of outputs larger than the caches
};

struct ClOptions {
  // Instances one work-item deforms (reading its rest vertex once); 0: the device's
  // choice (GPUs: 2 for the single bend with float32 normals, 4 with half normals
  // and for rigs; CPUs: 1).
  std::size_t instances_per_item = 0;
  RigDispatch dispatch = RigDispatch::kAuto;
  // The whole-body bend runs on its own kernel (faster); false runs it as a rig like
  // any other (for comparing the two).
  bool single_bend_kernel = true;
  // Vertex slots one work-item deforms, one per lane of OpenCL vectors over the output
  // planes (kernels/common/lanes.cl): 1, 8, 16 or 32; 0: the device's choice (GPUs 1;
  // CPUs vector code by construction, whatever the OpenCL compiler vectorises: on PoCL
  // two native float vectors, 32 lanes with AVX-512 and 16 with AVX2; elsewhere one,
  // 8 or 16). 32 lanes are a vector type of clang's, not OpenCL C's: PoCL only
  // (refused elsewhere). Lanes apply per batch: outputs in FinFlex's planes (a batch
  // whose OutputLayout equals planes_layout(instances, format) for either NormalFormat:
  // float32 positions, normals and tangents in float32 or half, slot order, previous
  // positions, if any, in float32 planes laid out as the positions (previous_layout as
  // planes_layout sets it); allocate(instances[, format]) makes one) are stored as
  // vectors, and so
  // is a vertex struct that its attributes fill in one buffer (transposed in registers,
  // finflex/cl_outputs.hpp lane_struct_options) unless it is staged, and so are
  // attributes each in a tightly packed array of its own; on CPUs
  // any other layout lane by lane through the one-slot stores of
  // kernels/common/outputs.cl, but the single bend's in mesh order or with previous
  // positions in another layout, and on GPUs every other layout, with one lane whatever
  // this asks:
  // lanes(outputs) says which.
  std::size_t lanes = 0;
  // With more than one lane: how the outputs are stored.
  OutputStores stores = OutputStores::kAuto;
  // A vertex struct of float32x3 attributes that fill it, in one buffer and slot order
  // (finflex/cl_outputs.hpp staged_struct_options), is written through local memory as
  // contiguous runs: true on GPUs (coalesced stores), false on CPUs (whose kernels of
  // more than one lane transpose a work-item's structs in registers and store whole
  // vectors: lane_struct_options). Only a layout of that kind is affected.
  enum class StructStores { kAuto, kStaged, kDirect };
  StructStores struct_stores = StructStores::kAuto;
  // Work-items per instance for the per-instance tables of the frame (rig_prepare: a
  // spine's running integrals): a power of two up to kGroupSize; 0: the device's
  // choice (GPUs: one per sample, up to kGroupSize; CPUs 1).
  std::size_t table_items = 0;
};

class FINFLEX_API ClDeformer {
 public:
  // Uploads the model: rest mesh planes over slots (each vertex in its first stage's
  // frame), the stage table and the rig's dispatch code. kInvalidMesh when the mesh
  // has more than 2^32 slots.
  ClDeformer(Context& context, const RiggedMesh& model, const ClOptions& options = {});
  ~ClDeformer();
  ClDeformer(const ClDeformer&) = delete;
  ClDeformer& operator=(const ClDeformer&) = delete;

  const RiggedMesh& model() const;
  Context& context() const;

  BatchLayout layout(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;
  // Allocates the outputs of `instances` instances in FinFlex's planes, normals and
  // tangents in `format`. kInvalidArgument for 0, kOutOfRange naming "instances" when
  // one attribute array would exceed the device's largest allocation or above
  // kMaxDeviceInstances. On a CPU device an attribute's buffer of 2 MiB or more is host
  // memory aligned to 2 MiB and advised as transparent huge pages (Linux), wrapped
  // with CL_MEM_USE_HOST_PTR: the kernels' stores then run faster, on far fewer
  // pages (docs/benchmarks.md, Swimming, "Outputs in huge pages"). For bind_host, align and
  // advise your own memory alike for the same gain.
  DeviceBatch allocate(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;

  // ---- Hand-off (finflex/output_layout.hpp, docs/handoff.md) ----
  // The vertices an output layout in `order` covers: the slots (slot_of_vertex(),
  // padding included) or the mesh's vertices.
  std::size_t output_vertices(VertexOrder order) const;
  // FinFlex's planes for `instances` instances as an OutputLayout, to start from.
  OutputLayout planes_layout(std::size_t instances,
                             NormalFormat format = NormalFormat::kFloat32) const;
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

  // Validates the job (ClJob::validate, then: the job's model is this deformer's,
  // and its outputs were allocated for this model with room for its instances:
  // "job.outputs" names what does not fit), checks its parameters (check_parameters)
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
  // True when enqueue() runs the single-bend kernel (RiggedMesh::is_single_bend and
  // ClOptions::single_bend_kernel).
  bool uses_single_bend_kernel() const;
  // Passes of the multi-pass path: one per (depth, chain position) that has a stage.
  std::size_t pass_count() const;
  // Float32 vertex records the multi-pass path moves through its scratch sets (reads
  // plus writes, all passes), per slot: 0 when no vertex has more than one stage.
  double scratch_records_per_slot() const;
  // Derived values per instance (a spine's running integrals; 0 when the rig has none):
  // the floats a ClJob::derived_buffer holds for each instance.
  std::size_t derived_floats_per_instance() const;
  // The path RigPath::kAuto resolves to for this model.
  RigPath automatic_path() const;
  // Instances one work-item deforms for outputs in FinFlex's planes in `format`, or in
  // `outputs`, with normals by `normals` (ClOptions; the shape may differ by mode).
  std::size_t instances_per_item(NormalFormat format,
                                 NormalMode normals = NormalMode::kRotate) const;
  std::size_t instances_per_item(const OutputLayout& outputs,
                                 NormalMode normals = NormalMode::kRotate) const;
  // Vertex slots one work-item deforms for outputs in FinFlex's planes (the same for
  // both normal formats), and for outputs in `outputs` (ClOptions::lanes).
  std::size_t lanes(NormalFormat format) const;
  std::size_t lanes(const OutputLayout& outputs) const;
  // True when a frame on `batch` writes it with streaming stores (ClOptions::stores;
  // only kernels of more than one lane have them).
  bool streams_outputs(const DeviceBatch& batch) const;

  // The work-group size along the slots (every plane stride is a multiple of it).
  static constexpr std::size_t kGroupSize = 64;
  // Instances (NDRange rows) a work-group of the kernels of more than one lane covers
  // (CPUs; one-lane kernels: 1): PoCL runs a work-group as one call, which loads the
  // kernel's constants before its loop over the work-items, and the group's 64 rest
  // slots stay in the first-level cache while its rows deform them. 4 rows against one:
  // the swim's body kernel on 2 threads of a Xeon, 1,000 fish, 8.57-8.91 ms a frame
  // against 8.71-9.70. 16 rows against 4: the whole swim frame 0.94-0.95 of the time
  // (medians of 16 rounds, two hosts), 32 rows 0.99, 8 rows 1.01; 16 threads alike; the
  // write-only kernel alike either way (docs/benchmarks.md, Swimming, "Sixteen rows").
  // Rows past the last instance are skipped in the kernels.
  static constexpr std::size_t kLaneGroupRows = 16;
  // The NDRange rows of a launch of `lanes`-lane kernels over `items_high` rows of
  // work-items: a whole number of work-groups of group_rows(lanes) rows.
  static constexpr std::size_t group_rows(std::size_t lanes) {
    return lanes > 1 ? kLaneGroupRows : 1;
  }
  static constexpr std::size_t launch_rows(std::size_t items_high, std::size_t lanes) {
    return (items_high + group_rows(lanes) - 1) / group_rows(lanes) * group_rows(lanes);
  }
  // Most stages on one vertex's path that the fused kernel is generated for.
  static constexpr std::size_t kMaxFusedStages = 64;

 private:
  friend class RigFrame;
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

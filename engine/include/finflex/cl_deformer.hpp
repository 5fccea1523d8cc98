// The OpenCL backend: one rest mesh on the device, N instances per launch, each with
// its own bend parameter m; one NDRange over (vertices x instances).
//
//   Context context;                                  // PoCL on the CPU, or a GPU
//   ClDeformer deformer(context, make_local_mesh(mesh, find_body_frame(mesh)));
//   DeviceBatch batch = deformer.allocate(4000);      // once
//   for each frame:
//     cl::Event done = deformer.enqueue(m_for_this_frame, settings, batch);
//     ... hand batch.positions / batch.normals (cl::Buffer) to the renderer, or read()
//
// Memory: the rest mesh takes 24 bytes per vertex (36 with tangents) once; every
// instance takes 24 bytes per vertex of output (positions + normals, float32), 36 with
// tangents, 18 and 24 with half normals and tangents (NormalFormat::kHalf), on
// plane_stride (vertex count rounded up to 64) vertices. 4,000 instances of the
// 10,786-vertex fish: 4,000 * 10,816 * 24 B = 1.04 GB.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/bend.hpp"
#include "finflex/cl_context.hpp"
#include "finflex/local_mesh.hpp"

namespace finflex {

// Device-side outputs of one batch, allocated once and reused every frame.
struct DeviceBatch {
  BatchLayout layout;
  cl::Buffer positions;  // layout.attribute_elements() floats, finflex/batch.hpp planes
  cl::Buffer normals;
  cl::Buffer tangents;    // a placeholder of one float when the mesh has no tangents
  cl::Buffer parameters;  // per instance: m, or a rig's parameter values

  // Float32 intermediates of the multi-pass rig path, allocated on first use: up to
  // two sets (positions, normals, tangents) that the passes ping-pong between; the
  // last pass writes the outputs above.
  std::vector<cl::Buffer> scratch;

  // Host staging of the parameter uploads, a ring: a non-blocking upload reads its
  // values until it completes, which the last kernel of its frame (`staging_done`,
  // after it in the in-order queue) proves. Reusing a slot waits for the frame that
  // used it, kStagingSlots frames ago: no event of its own per upload.
  static constexpr std::size_t kStagingSlots = 3;
  std::array<std::vector<float>, kStagingSlots> staging;
  std::array<cl::Event, kStagingSlots> staging_done;
  std::size_t next_staging = 0;

  // Identifies these buffers (set by allocate(), unique in the process; 0: none), so
  // deformers set kernel arguments only when a frame goes to another batch. Replace a
  // batch by allocating a new one, never by assigning its buffers.
  std::uint64_t serial = 0;
};

// A deformer's kernel and the batch its arguments were last set for: a frame on the
// same batch as the last one is a parameter upload and a launch, without setting
// arguments again.
struct BoundKernel {
  cl::Kernel kernel;
  std::uint64_t batch_serial = 0;
  std::size_t scratch_buffers = 0;

  bool bound_to(const DeviceBatch& batch) const {
    return batch.serial != 0 && batch_serial == batch.serial &&
           scratch_buffers == batch.scratch.size();
  }
  void mark_bound(const DeviceBatch& batch) {
    batch_serial = batch.serial;
    scratch_buffers = batch.scratch.size();
  }
};

class ClDeformer {
 public:
  // Uploads the rest mesh (float32 planes) once. `instances_per_item`: instances each
  // work-item deforms; 0 takes instances_per_work_item() of the device.
  ClDeformer(Context& context, const LocalMesh& mesh, std::size_t instances_per_item = 0);

  const LocalMesh& mesh() const { return mesh_; }
  BatchLayout layout(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;

  // Allocates the outputs of `instances` instances, normals and tangents in `format`.
  // Throws kInvalidArgument for 0, and kOutOfRange naming `instances` when one
  // attribute array would exceed the device's largest allocation.
  DeviceBatch allocate(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;

  // Checks m (checked_bend_params; its size must equal the batch's instance count),
  // uploads it without blocking, and enqueues the bend after `wait`. Returns the
  // kernel's event (profiling enabled); nothing waits on the host except for the
  // previous frame's parameter upload of the same batch.
  cl::Event enqueue(const std::vector<float>& m, const BendSettings& settings, DeviceBatch& batch,
                    bool clamp = false, const std::vector<cl::Event>* wait = nullptr);

  // Blocking read of a batch (waits for the queue's work on it).
  DeformedBatch<float> read(const DeviceBatch& batch);

  // The work-group size used along the vertices (plane_stride is a multiple of it).
  static constexpr std::size_t kLocalSize = 64;

 private:
  Context& context_;
  LocalMesh mesh_;
  std::size_t plane_stride_ = 0;
  cl::Buffer rest_;
  std::vector<cl_float4> back_transform_;  // origin, s e_x, s e_y, s e_z, e_x, e_y, e_z
  std::size_t instances_per_item_ = 0;     // 0: instances_per_work_item() of the device
  std::size_t per_item(NormalFormat format) const;
  // By (mode, normals, format): created on first use, no per-frame creation or strings.
  std::map<std::tuple<BendMode, NormalMode, NormalFormat>, BoundKernel> kernels_;

  BoundKernel& bend_kernel(const BendSettings& settings, NormalFormat format);
};

// Build options specialising the kernels (-D FF_BEND_EXACT=...).
std::string bend_build_options(const BendSettings& settings, bool tangents, NormalFormat format,
                               std::size_t instances_per_item);

// Instances one work-item deforms (reading its rest vertex once): on GPUs, whose rate
// of work-items, not of bytes, limits one instance per work-item, 2 with float32
// normals and 4 with half normals (fewer bytes per instance); 1 on CPUs.
std::size_t instances_per_work_item(const DeviceDescription& device,
                                    NormalFormat format = NormalFormat::kFloat32);

// What the write-only reference kernel writes: one value everywhere (no arithmetic at
// all), or values that differ per vertex and instance (a few integer operations; GPUs
// may compress uniform data on its way to memory and write it faster than any real
// output could go).
enum class WriteValues {
  kDeviceDefault,  // kVarying on GPUs, kConstant on CPUs
  kConstant,
  kVarying,
};

// The write-only reference kernel over `batch`'s outputs: writes positions and normals
// (in the batch's format), in the bend kernel's NDRange, so that benchmarks can measure
// the device's write bandwidth next to the deformers.
// `instances_per_item`: 0 takes instances_per_work_item() of the device.
cl::Event enqueue_write_only(Context& context, DeviceBatch& batch,
                             std::size_t instances_per_item = 0,
                             WriteValues values = WriteValues::kDeviceDefault);

}  // namespace finflex

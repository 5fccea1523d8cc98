// Deforming rigged meshes (finflex/rig.hpp): every instance has one value per rig
// parameter; each vertex goes through its component's chain, then its ancestors'.
//
//   Rig rig = resolve_rig(load_rig_file("data/rigs/blub.rig.json"), mesh);
//   ClRigDeformer deformer(context, mesh, rig);
//   DeviceBatch batch = deformer.allocate(1000);
//   RigParameters values(rig, 1000);                       // all zero: the rest pose
//   values.set(i, "body_m", 0.4f); values.set(i, "tail_angle", -0.3f);
//   deformer.enqueue(values, NormalMode::kJacobian, batch); // fused by default
//
// Outputs are in slots: vertices reordered so that every component is a contiguous
// range of whole work-groups (finflex/batch.hpp planes over slots); slot_of_vertex()
// maps a mesh vertex to its slot, remapped_indices() are the mesh's triangles over
// slots (draw the outputs with them), and read() hands back a batch whose accessors
// take mesh vertex indices.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/batch.hpp"
#include "finflex/bend.hpp"
#include "finflex/cl_context.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/mesh.hpp"
#include "finflex/rig.hpp"

namespace finflex {

// Per-instance parameter values: instance_count rows of rig.params.size() values.
class RigParameters {
 public:
  RigParameters(const Rig& rig, std::size_t instance_count);

  std::size_t instance_count() const { return instance_count_; }
  std::size_t param_count() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  // Sets a value by parameter name (kInvalidArgument naming an unknown one or an
  // instance out of range); values are checked when a deformer uses them.
  void set(std::size_t instance, const std::string& name, float value);
  float get(std::size_t instance, std::size_t param) const {
    return values_[instance * names_.size() + param];
  }
  const std::vector<float>& values() const { return values_; }  // row-major
  std::vector<float>& values() { return values_; }

 private:
  std::vector<std::string> names_;
  std::size_t instance_count_ = 0;
  std::vector<float> values_;
};

// The valid range of each parameter: the tightest over the stages that read it
// (bend: |m| <= 0.5 / x_max of the stage (13); hinge: |angle| <= pi).
std::vector<double> rig_param_limits(const Rig& rig);

// Checks every value (NaN/Inf: kInvalidArgument; out of range: kOutOfRange, both naming
// "name[instance]", the value and the range) or clamps out-of-range ones into their
// range when `clamp`, writing the result to `out` (capacity reused).
void check_rig_params_into(const Rig& rig, const std::vector<double>& limits,
                           const RigParameters& parameters, bool clamp, std::vector<float>& out);
// The same checks without copying: `clamped`, when given, must already hold the
// values; out-of-range ones are clamped in it.
void check_rig_params(const Rig& rig, const std::vector<double>& limits,
                      const RigParameters& parameters, bool clamp, std::vector<float>* clamped);

// How a batch of a rig runs on a device.
enum class RigPath {
  kAuto,    // fused where it applies (every path of at most kMaxFusedStages stages)
  kFused,   // one pass: each vertex applies its whole bottom-up path in registers
  kPasses,  // one pass per (hierarchy level, chain position), ping-pong buffers; a
            // pass touches only the vertices it has a stage for
};
const char* to_string(RigPath path);
RigPath parse_rig_path(const std::string& text, const std::string& field = "path");

// The CPU reference: the chains applied literally, stage by stage, in double
// precision, in the mesh's own vertex order.
class RigReference {
 public:
  RigReference(const Mesh& mesh, const Rig& rig);
  DeformedBatch<double> run(const RigParameters& parameters, NormalMode normals,
                            bool clamp = false) const;

 private:
  Mesh mesh_;
  Rig rig_;
  std::vector<double> limits_;
  std::vector<std::size_t> component_of_vertex_;
};

// How the generated rig kernels tell the work-groups' stages apart (every branch is
// uniform over a work-group).
enum class RigDispatch {
  kAuto,          // kPerComponent on GPUs, kByPathShape on CPUs
  kPerComponent,  // a branch per component, its stages compiled in: fewest instructions
  kByPathShape,   // a branch per run of components with the same deformers along their
                  // paths, stages read from a table: fewest branches, which PoCL's
                  // work-group vectoriser needs
};

// Instances one work-item of the rig kernels deforms: 4 on GPUs (the rig's stage
// frames and parameters are read once for them), 1 on CPUs.
std::size_t rig_instances_per_work_item(const DeviceDescription& device);

class ClRigDeformer {
 public:
  // Reorders the vertices into slots, uploads the rest mesh and the stage frames once.
  // `instances_per_item`: instances each work-item deforms; 0 takes
  // rig_instances_per_work_item() of the device. `dispatch`: see RigDispatch.
  ClRigDeformer(Context& context, const Mesh& mesh, const Rig& rig,
                std::size_t instances_per_item = 0, RigDispatch dispatch = RigDispatch::kAuto);

  const Rig& rig() const { return rig_; }
  BatchLayout layout(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;
  const std::vector<std::uint32_t>& slot_of_vertex() const { return slot_of_vertex_; }
  const std::vector<std::uint32_t>& remapped_indices() const { return remapped_indices_; }
  // Passes the multi-pass path runs: one per (depth, chain position) that has a stage.
  std::size_t pass_count() const { return pass_count_; }
  // Float32 vertex records the multi-pass path moves through its scratch sets (reads
  // plus writes, all passes), per slot: 0 when no vertex has more than one stage; each
  // vertex also reads the shared rest mesh once and writes its output once.
  double scratch_records_per_slot() const { return scratch_records_per_slot_; }
  // The path kAuto resolves to for this rig.
  RigPath automatic_path() const { return automatic_path_; }

  DeviceBatch allocate(std::size_t instances, NormalFormat format = NormalFormat::kFloat32) const;

  // Checks the values (check_rig_params_into), uploads them without blocking, and
  // enqueues the deformation; returns the event of the last kernel.
  // `kernel_events`, when given, receives the event of every kernel launched (one for
  // the fused path, one per pass), e.g. for profiling.
  cl::Event enqueue(const RigParameters& parameters, NormalMode normals, DeviceBatch& batch,
                    RigPath path = RigPath::kAuto, bool clamp = false,
                    const std::vector<cl::Event>* wait = nullptr,
                    std::vector<cl::Event>* kernel_events = nullptr);

  // Throws as enqueue() would for these parameters, touching nothing.
  void check(const RigParameters& parameters, bool clamp) const;

  // Blocking read; the result's accessors take mesh vertex indices.
  DeformedBatch<float> read(const DeviceBatch& batch);

  // Most stages on one vertex's path that the fused kernel is generated for.
  static constexpr std::size_t kMaxFusedStages = 64;

 private:
  Context& context_;
  Rig rig_;
  std::vector<double> limits_;
  std::vector<float> bounds_tile_;  // detail::rig_bounds_tile(limits_)
  std::size_t vertex_count_ = 0;
  std::size_t slot_count_ = 0;
  std::size_t pass_count_ = 0;
  // The fused path's kernels rig_fused_<r>: the work-groups each covers.
  std::vector<std::pair<std::size_t, std::size_t>> fused_launches_;
  std::size_t scratch_sets_ = 0;
  double scratch_records_per_slot_ = 0.0;
  bool tangents_ = false;
  std::size_t instances_per_item_ = 1;
  std::vector<std::uint32_t> slot_of_vertex_;
  std::vector<std::uint32_t> remapped_indices_;
  cl::Buffer rest_positions_, rest_normals_, rest_tangents_;
  cl::Buffer stages_;
  cl::Buffer group_paths_;
  ProgramSource program_;
  RigPath automatic_path_ = RigPath::kFused;
  // By (r for rig_fused_r, then fused launches + q for rig_pass_q, normal mode, normal
  // format): created on first use, looked up without building strings every frame.
  std::map<std::tuple<std::size_t, NormalMode, NormalFormat>, BoundKernel> kernels_;

  BoundKernel& kernel(std::size_t index, NormalMode normals, NormalFormat format);
  void set_batch_args(cl::Kernel& kernel, cl_uint first, const DeviceBatch& batch) const;
  // Sets the kernel's arguments if it was last bound to another batch (`leading`: the
  // buffers before the batch's), launches it over work-groups [first_group, end_group)
  // x instances; its event goes to `done` when given and to `kernel_events`.
  void launch(BoundKernel& bound, const DeviceBatch& batch,
              std::initializer_list<const cl::Buffer*> leading, std::size_t first_group,
              std::size_t end_group, std::vector<cl::Event>* kernel_events, cl::Event* done);
  void ensure_scratch(DeviceBatch& batch, std::size_t sets) const;
};

// Several rigged meshes (e.g. two species) deformed in one frame: each entry is a
// deformer with its own instances, batch and parameters; enqueue() launches them all
// on the context's queue, each after its own parameter upload, without waiting.
class RigFrame {
 public:
  // Adds `instances` instances of `deformer`'s mesh (the deformer must outlive the
  // frame); returns the entry's index. Parameters start at the rest pose (zeros).
  std::size_t add(ClRigDeformer& deformer, std::size_t instances);

  std::size_t size() const { return entries_.size(); }
  RigParameters& parameters(std::size_t entry) { return at(entry).parameters; }
  DeviceBatch& batch(std::size_t entry) { return at(entry).batch; }

  // One event per entry, in order. Every entry's parameters are checked before any
  // is launched.
  std::vector<cl::Event> enqueue(NormalMode normals, RigPath path = RigPath::kAuto,
                                 bool clamp = false);

 private:
  struct Entry {
    ClRigDeformer* deformer;
    DeviceBatch batch;
    RigParameters parameters;
  };
  std::vector<Entry> entries_;

  Entry& at(std::size_t entry);
};

}  // namespace finflex

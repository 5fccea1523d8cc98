// What a deformation job deforms: a rest mesh with its resolved rig (finflex/rig.hpp),
// validated together once. Both backends take it: the CPU reference applies the
// stages literally, the OpenCL backend uploads it once per device.
//
//   RiggedMesh fish(mesh, resolve_rig(load_rig_file("data/rigs/blub.rig.json"), mesh));
//   RiggedMesh bent = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
//
// Thread-safety: a RiggedMesh does not change after construction; any number of
// threads may read it (deformers and reference jobs on several threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "finflex/body_frame.hpp"
#include "finflex/export.hpp"
#include "finflex/mesh.hpp"
#include "finflex/rig.hpp"

namespace finflex {

class FINFLEX_API RiggedMesh {
 public:
  // Validates the mesh (validate_mesh), the rig's structure (kInvalidArgument, field
  // "rig": parents before children, the limits kMaxRigDepth and kMaxRigPathStages,
  // subtree_end, stage parameters in range and of the right size) and that the rig's
  // components take every vertex exactly once: kInvalidArgument (field "rig") naming
  // the first vertex that belongs to no component or to two. Mesh and rig are copied.
  RiggedMesh(Mesh mesh, Rig rig);

  // The paper's whole-body bend: single_bend_rig(mesh, frame, mode).
  static RiggedMesh single_bend(const Mesh& mesh, const BodyFrame& frame, BendMode mode);

  const Mesh& mesh() const { return mesh_; }
  const Rig& rig() const { return rig_; }
  std::size_t vertex_count() const { return mesh_.vertex_count(); }
  // Per-instance values a job gives for this model (Rig::values_per_instance()).
  std::size_t values_per_instance() const { return values_per_instance_; }
  // The component each mesh vertex belongs to.
  const std::vector<std::size_t>& component_of_vertex() const { return component_of_vertex_; }
  // Rig::path of every component, computed once.
  const std::vector<std::vector<StageRef>>& paths() const { return paths_; }
  // Stages on the longest path.
  std::size_t longest_path() const { return longest_path_; }
  // True when the rig is one component with one bend stage (the paper's whole-body
  // bend): the OpenCL backend has a faster kernel for it.
  bool is_single_bend() const;
  // Identifies the model (copies share it), so a backend can tell that a job's model
  // is the one it was built for.
  std::uint64_t id() const { return id_; }

 private:
  Mesh mesh_;
  Rig rig_;
  std::size_t values_per_instance_ = 0;
  std::vector<std::size_t> component_of_vertex_;
  std::vector<std::vector<StageRef>> paths_;
  std::size_t longest_path_ = 0;
  std::uint64_t id_ = 0;
};

}  // namespace finflex

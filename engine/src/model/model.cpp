#include "finflex/model.hpp"

#include <algorithm>
#include <atomic>
#include <string>

#include "finflex/error.hpp"
#include "rig/structure.hpp"

namespace finflex {
namespace {

std::uint64_t next_model_id() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

}  // namespace

RiggedMesh::RiggedMesh(Mesh mesh, Rig rig) : mesh_(std::move(mesh)), rig_(std::move(rig)) {
  validate_mesh(mesh_);
  detail::check_rig_structure(rig_);
  const std::size_t none = rig_.components.size();
  component_of_vertex_.assign(mesh_.vertex_count(), none);
  for (std::size_t c = 0; c < rig_.components.size(); ++c) {
    for (std::uint32_t v : rig_.components[c].vertices) {
      if (v >= mesh_.vertex_count() || component_of_vertex_[v] != none) {
        throw Error(ErrorCode::kInvalidArgument, "rig",
                    "rig: component '" + rig_.components[c].name + "' takes vertex " +
                        std::to_string(v) +
                        (v >= mesh_.vertex_count()
                             ? ", beyond the mesh's " + std::to_string(mesh_.vertex_count())
                             : ", which '" + rig_.components[component_of_vertex_[v]].name +
                                   "' takes too"));
      }
      component_of_vertex_[v] = c;
    }
  }
  const auto orphan = std::find(component_of_vertex_.begin(), component_of_vertex_.end(), none);
  if (orphan != component_of_vertex_.end()) {
    throw Error(ErrorCode::kInvalidArgument, "rig",
                "rig: vertex " + std::to_string(orphan - component_of_vertex_.begin()) +
                    " belongs to no component");
  }
  paths_.reserve(rig_.components.size());
  for (std::size_t c = 0; c < rig_.components.size(); ++c) {
    paths_.push_back(rig_.path(c));
    longest_path_ = std::max(longest_path_, paths_.back().size());
  }
  values_per_instance_ = rig_.values_per_instance();
  id_ = next_model_id();
}

RiggedMesh RiggedMesh::single_bend(const Mesh& mesh, const BodyFrame& frame, BendMode mode) {
  return RiggedMesh(mesh, single_bend_rig(mesh, frame, mode));
}

bool RiggedMesh::is_single_bend() const {
  return rig_.components.size() == 1 && rig_.components[0].chain.size() == 1 &&
         std::string(rig_.components[0].chain[0].deformer->name) == "bend";
}

}  // namespace finflex

#include "cl/slot_layout.hpp"

#include <algorithm>
#include <utility>

#include "finflex/error.hpp"

namespace finflex::detail {
namespace {

std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// A stage's derived values, rounded up to 8 floats: every stage's start 32-byte
// aligned (DeformerType::derived_count), and so every instance's row.
std::size_t aligned_derived(const RigStage& stage) {
  return round_up(stage.deformer->derived_count(stage.options), 8);
}

// Derived values before stage k (stages in rig order).
std::size_t derived_offset_of(const Rig& rig, std::size_t k) {
  std::size_t offset = 0, index = 0;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) {
      if (index++ == k) return offset;
      if (stage.deformer->derived_count) offset += aligned_derived(stage);
    }
  }
  return offset;
}

// The first stage on the component's path (its own chain, then its ancestors') that
// looks vertices up in a table along x (a deformer with derived values), or null.
const RigStage* first_table_stage(const Rig& rig, std::size_t component) {
  // A resolved rig is a tree: the walk up ends within the component count.
  for (std::size_t steps = 0; steps < rig.components.size(); ++steps) {
    const RigComponent& on_path = rig.components[component];
    for (const RigStage& stage : on_path.chain) {
      if (stage.deformer->derived_count != nullptr) return &stage;
    }
    if (on_path.parent < 0) break;
    component = static_cast<std::size_t>(on_path.parent);
  }
  return nullptr;
}

// The component's vertices in slot order: by rest x in the frame of the first table
// stage on its path (ties by vertex index), else as they are (ascending). A fin under
// a spine is sorted along the spine too: its vertices reach the spine's table after
// its own hinge, which moves them little along the body.
std::vector<std::uint32_t> vertices_in_slot_order(const Rig& rig, std::size_t component,
                                                  const std::vector<glm::vec3>& positions) {
  std::vector<std::uint32_t> order = rig.components[component].vertices;
  const RigStage* table = first_table_stage(rig, component);
  if (table == nullptr) return order;
  std::vector<std::pair<double, std::uint32_t>> keyed;
  keyed.reserve(order.size());
  for (std::uint32_t v : order) {
    keyed.emplace_back(table->frame.point_to_local(glm::dvec3(positions[v])).x, v);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

std::size_t values_offset(const Rig& rig, const RigStage& stage) {
  return rig.parameters[stage.param].offset;
}

SlotLayout make_slot_layout(const Rig& rig, const std::vector<glm::vec3>& positions,
                            std::size_t group_size) {
  const std::size_t vertex_count = positions.size();
  SlotLayout slots;
  slots.slot_of_vertex.assign(vertex_count, 0);
  slots.first_slot.push_back(0);
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    std::size_t slot = slots.first_slot.back();
    for (std::uint32_t v : vertices_in_slot_order(rig, c, positions))
      slots.slot_of_vertex[v] = static_cast<std::uint32_t>(slot++);
    slots.first_slot.push_back(round_up(slot, group_size));
  }
  slots.slot_count = std::max(slots.first_slot.back(), group_size);
  if (slots.slot_count > 0xffffffffu) {
    throw Error(ErrorCode::kInvalidMesh, "positions",
                "the mesh needs " + std::to_string(slots.slot_count) +
                    " vertex slots, more than the kernels' 2^32");
  }
  slots.vertex_of_slot.assign(slots.slot_count, -1);
  for (std::size_t v = 0; v < vertex_count; ++v)
    slots.vertex_of_slot[slots.slot_of_vertex[v]] = static_cast<std::int64_t>(v);
  return slots;
}

RestPlanes make_rest_planes(const RiggedMesh& model, const SlotLayout& slots) {
  const Rig& rig = model.rig();
  const Mesh& mesh = model.mesh();
  RestPlanes rest;
  const std::size_t n = slots.slot_count;
  rest.positions.assign(3 * n, 0.0f);
  rest.normals.assign(3 * n, 0.0f);
  if (mesh.has_tangents()) rest.tangents.assign(4 * n, 0.0f);  // x, y, z, handedness
  auto put = [n](std::vector<float>& planes, std::size_t slot, const glm::dvec3& value) {
    for (int c = 0; c < 3; ++c) planes[static_cast<std::size_t>(c) * n + slot] = float(value[c]);
  };
  for (std::size_t slot = 0; slot < n; ++slot) {  // padding: harmless values
    put(rest.normals, slot, glm::dvec3(0.0, 0.0, 1.0));
    if (!rest.tangents.empty()) {
      put(rest.tangents, slot, glm::dvec3(1.0, 0.0, 0.0));
      rest.tangents[3 * n + slot] = 1.0f;
    }
  }
  for (std::size_t c = 0; c < rig.components.size(); ++c) {
    const std::vector<StageRef>& path = model.paths()[c];
    const BodyFrame first = path.empty() ? BodyFrame::identity() : rig.stage(path.front()).frame;
    for (std::uint32_t v : rig.components[c].vertices) {
      const std::size_t slot = slots.slot_of_vertex[v];
      // (2): p = R (p_b - origin) / s_x, n = R n_b, in double before rounding.
      put(rest.positions, slot, first.point_to_local(glm::dvec3(mesh.positions[v])));
      put(rest.normals, slot, first.vector_to_local(glm::normalize(glm::dvec3(mesh.normals[v]))));
      if (!rest.tangents.empty()) {
        put(rest.tangents, slot,
            first.vector_to_local(glm::normalize(glm::dvec3(mesh.tangents[v]))));
        rest.tangents[3 * n + slot] = mesh.tangents[v].w;
      }
    }
    // The component's padding repeats its last slot's position, so that its slots stay
    // sorted by x where they are (make_slot_layout; DeformerType::cl_rest_function).
    const std::size_t count = rig.components[c].vertices.size();
    for (std::size_t slot = slots.first_slot[c] + count;
         count > 0 && slot < slots.first_slot[c + 1]; ++slot) {
      for (std::size_t axis = 0; axis < 3; ++axis)
        rest.positions[axis * n + slot] = rest.positions[axis * n + slot - 1];
    }
  }
  return rest;
}

std::size_t stage_index(const Rig& rig, std::size_t component, std::size_t stage) {
  std::size_t index = 0;
  for (std::size_t c = 0; c < component; ++c) index += rig.components[c].chain.size();
  return index + stage;
}

std::size_t stage_count(const Rig& rig) { return stage_index(rig, rig.components.size(), 0); }

std::size_t derived_per_instance(const Rig& rig) {
  return derived_offset_of(rig, stage_count(rig));
}

std::size_t derived_offset(const Rig& rig, std::size_t component, std::size_t stage) {
  return derived_offset_of(rig, stage_index(rig, component, stage));
}

std::size_t stage_table_rows(const Rig& rig) { return stage_count(rig) + 1; }

std::vector<float> stage_table(const Rig& rig) {
  const std::size_t count = stage_table_rows(rig);
  std::vector<float> table(kStageValues * count, 0.0f);
  // A row per stage, in rig order, then the root's frame (for placing from mesh
  // coordinates when the root has no stage).
  std::vector<const RigStage*> rows;
  for (const RigComponent& component : rig.components) {
    for (const RigStage& stage : component.chain) rows.push_back(&stage);
  }
  RigStage root;
  root.frame = rig.components.front().frame;
  rows.push_back(&root);
  for (std::size_t k = 0; k < count; ++k) {
    const RigStage& stage = *rows[k];
    const BodyFrame& f = stage.frame;
    const StageConstants c = stage.deformer
                                 ? stage.deformer->stage_constants(stage.options, stage.geometry)
                                 : StageConstants{};
    const double offset = stage.deformer ? double(values_offset(rig, stage)) : 0.0;
    const double derived = double(derived_offset_of(rig, k));
    // kernels/common/stage_frame.cl's layout.
    // clang-format off
    const double values[kStageValues] = {
        f.axis_x.x, f.axis_x.y, f.axis_x.z, 1.0 / f.length,   // 0-3
        f.axis_y.x, f.axis_y.y, f.axis_y.z, c[0],             // 4-7
        f.axis_z.x, f.axis_z.y, f.axis_z.z, offset,           // 8-11
        f.origin.x, f.origin.y, f.origin.z, f.length,         // 12-15
        c[1], c[2], c[3], derived};                           // 16-19
    // clang-format on
    for (std::size_t v = 0; v < kStageValues; ++v)
      table[v * count + k] = static_cast<float>(values[v]);
  }
  return table;
}

}  // namespace finflex::detail

#include "finflex/detail_levels.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "finflex/error.hpp"
#include "surface_distance.hpp"

namespace finflex {

namespace {

constexpr std::uint32_t kUnplaced = ~std::uint32_t(0);

// The simplifier's error limit, relative to the mesh's extent: none, so each step goes
// to its triangle target (the level choice decides where the error is acceptable).
constexpr float kNoErrorLimit = 1.0f;

// A coarser level must keep at most this share of the finer level's triangles.
constexpr double kLeastReduction = 0.75;

constexpr std::size_t kAcrossParts = ~std::size_t(0);

// The component whose own triangle the one at index t is (all three vertices in it),
// else kAcrossParts.
std::size_t part_of_triangle(const std::vector<std::size_t>& component_of,
                             const std::vector<std::uint32_t>& indices, std::size_t t) {
  const std::size_t c = component_of[indices[t]];
  return component_of[indices[t + 1]] == c && component_of[indices[t + 2]] == c ? c : kAcrossParts;
}

// The simplifier's target for `indices` (a whole number of triangles, at least one).
std::size_t index_target(const std::vector<std::uint32_t>& indices, double ratio) {
  return std::max<std::size_t>(3,
                               std::size_t(std::llround(double(indices.size() / 3) * ratio)) * 3);
}

// Whether `coarser` has triangles and at most kLeastReduction of `finer`'s.
bool reduces(const std::vector<std::uint32_t>& finer, const std::vector<std::uint32_t>& coarser) {
  return !coarser.empty() && double(coarser.size()) <= kLeastReduction * double(finer.size());
}

// Whether every part with triangles of its own in `finer` keeps some in `coarser`
// (a fin stays a fin: something of it moves with its hinge).
bool keeps_every_part(const RiggedMesh& full, const std::vector<std::uint32_t>& finer,
                      const std::vector<std::uint32_t>& coarser) {
  const auto owned = [&](const std::vector<std::uint32_t>& indices) {
    std::vector<bool> has(full.rig().components.size(), false);
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
      const std::size_t c = part_of_triangle(full.component_of_vertex(), indices, t);
      if (c != kAcrossParts) has[c] = true;
    }
    return has;
  };
  const std::vector<bool> before = owned(finer), after = owned(coarser);
  for (std::size_t c = 0; c < before.size(); ++c) {
    if (before[c] && !after[c]) return false;
  }
  return true;
}

// One step of the cascade: `indices` (the finer level's triangles, input vertex ids)
// simplified component by component towards `ratio` of each one's triangles, borders
// locked, triangles across components kept as they are (and a component the
// simplifier would remove whole). Returns the triangles and
// the step's error relative to the mesh's extent (the largest component's).
std::pair<std::vector<std::uint32_t>, float> simplify_step(
    const RiggedMesh& full, const std::vector<std::uint32_t>& indices, double ratio) {
  const std::vector<std::size_t>& component_of = full.component_of_vertex();
  std::vector<std::vector<std::uint32_t>> within(full.rig().components.size());
  std::vector<std::uint32_t> out;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::size_t c = part_of_triangle(component_of, indices, t);
    if (c != kAcrossParts) {
      within[c].insert(within[c].end(), indices.begin() + std::ptrdiff_t(t),
                       indices.begin() + std::ptrdiff_t(t + 3));
    } else {
      out.insert(out.end(), indices.begin() + std::ptrdiff_t(t),
                 indices.begin() + std::ptrdiff_t(t + 3));
    }
  }
  const std::vector<glm::vec3>& positions = full.mesh().positions;
  float worst = 0.0f;
  std::vector<std::uint32_t> simplified;
  for (const std::vector<std::uint32_t>& triangles : within) {
    if (triangles.empty()) continue;
    const std::size_t target = index_target(triangles, ratio);
    simplified.resize(triangles.size());
    float error = 0.0f;
    const std::size_t count = meshopt_simplify(
        simplified.data(), triangles.data(), triangles.size(), &positions[0].x, positions.size(),
        sizeof(glm::vec3), target, kNoErrorLimit, meshopt_SimplifyLockBorder, &error);
    if (count == 0) {
      // Collapsed to nothing (a small closed part): the part stays as it was.
      out.insert(out.end(), triangles.begin(), triangles.end());
      continue;
    }
    out.insert(out.end(), simplified.begin(), simplified.begin() + std::ptrdiff_t(count));
    worst = std::max(worst, error);
  }
  return {std::move(out), worst};
}

// The other step: the whole of the finer level's triangles simplified at once, the
// borders between body and fins free (edges across them collapse too; every vertex
// kept stays in its own part, so fins still follow their hinges, and triangles across
// the parts grow), or where that stalls, clustered (meshoptimizer's sloppy
// simplifier). Both keep a subset of the vertices. Empty when every triangle goes.
std::pair<std::vector<std::uint32_t>, float> whole_mesh_step(
    const RiggedMesh& full, const std::vector<std::uint32_t>& indices, double ratio) {
  const std::vector<glm::vec3>& positions = full.mesh().positions;
  const std::size_t target = index_target(indices, ratio);
  std::vector<std::uint32_t> out(indices.size());
  float error = 0.0f;
  std::size_t count =
      meshopt_simplify(out.data(), indices.data(), indices.size(), &positions[0].x,
                       positions.size(), sizeof(glm::vec3), target, kNoErrorLimit, 0, &error);
  out.resize(count);
  if (!reduces(indices, out)) {
    out.resize(indices.size());
    count =
        meshopt_simplifySloppy(out.data(), indices.data(), indices.size(), &positions[0].x,
                               positions.size(), sizeof(glm::vec3), target, kNoErrorLimit, &error);
  }
  out.resize(count);
  return {std::move(out), error};
}

// The level over the first `vertex_count` vertices of the new order: the input's
// attributes and rig moved to it, `indices` (input vertex ids) renumbered.
RiggedMesh level_model(const RiggedMesh& full, const std::vector<std::uint32_t>& new_of,
                       const std::vector<std::uint32_t>& full_of, std::size_t vertex_count,
                       const std::vector<std::uint32_t>& indices, bool keep_groups) {
  const Mesh& in = full.mesh();
  Mesh mesh;
  mesh.positions.reserve(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const std::uint32_t from = full_of[v];
    mesh.positions.push_back(in.positions[from]);
    if (in.has_normals()) mesh.normals.push_back(in.normals[from]);
    if (in.has_tangents()) mesh.tangents.push_back(in.tangents[from]);
    if (!in.texcoords.empty()) mesh.texcoords.push_back(in.texcoords[from]);
  }
  mesh.indices.reserve(indices.size());
  for (std::uint32_t v : indices) mesh.indices.push_back(new_of[v]);
  if (keep_groups) mesh.groups = in.groups;  // level 0: the same triangles in the same order
  Rig rig = full.rig();
  for (RigComponent& component : rig.components) {
    std::vector<std::uint32_t> kept;
    for (std::uint32_t v : component.vertices) {
      if (new_of[v] < vertex_count) kept.push_back(new_of[v]);
    }
    std::sort(kept.begin(), kept.end());
    component.vertices = std::move(kept);
  }
  return RiggedMesh(std::move(mesh), std::move(rig));
}

void check_bound_count(const Rig& rig, const std::vector<double>& value_bounds) {
  if (value_bounds.size() != rig.parameters.size()) {
    throw Error(ErrorCode::kInvalidArgument, "value_bounds",
                "value_bounds: " + std::to_string(value_bounds.size()) + " values for a rig of " +
                    std::to_string(rig.parameters.size()) + " parameters");
  }
}

// The coarsest level again, its rig without the stages below the root.
DetailLevel frozen_level(const DetailLevel& coarsest, const std::vector<double>& value_bounds) {
  Rig rig = coarsest.model.rig();
  for (std::size_t c = 1; c < rig.components.size(); ++c) rig.components[c].chain.clear();
  DetailLevel frozen{RiggedMesh(coarsest.model.mesh(), std::move(rig)), coarsest.vertex_count,
                     coarsest.triangle_count, 0.0, true};
  frozen.geometric_error =
      coarsest.geometric_error + frozen_fin_error(coarsest.model, value_bounds);
  return frozen;
}

bool has_stages_below_root(const Rig& rig) {
  for (std::size_t c = 1; c < rig.components.size(); ++c) {
    if (!rig.components[c].chain.empty()) return true;
  }
  return false;
}

// How far `stage` moves the rest point `p` (mesh coordinates) at every value `value`,
// in mesh units.
double stage_displacement(const RigStage& stage, const glm::dvec3& p, double value) {
  const glm::dvec3 local = stage.frame.point_to_local(p);
  const std::vector<double> values(stage.deformer->value_count(stage.options), value);
  const SecantSample s =
      stage.deformer->secant(local.x, values.data(), stage.options, stage.geometry);
  const glm::dvec3 moved = s.f + glm::dvec3(0.0, local.y, 0.0) + local.z * s.n;
  return glm::length(moved - local) * stage.frame.length;
}

}  // namespace

double frozen_fin_error(const RiggedMesh& model, const std::vector<double>& value_bounds) {
  const Rig& rig = model.rig();
  if (!value_bounds.empty()) check_bound_count(rig, value_bounds);
  const auto bound_of = [&](std::size_t param) {
    return value_bounds.empty() ? rig.parameters[param].limit : value_bounds[param];
  };
  const std::vector<glm::vec3>& positions = model.mesh().positions;
  double worst = 0.0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const std::size_t component = model.component_of_vertex()[v];
    if (component == 0) continue;  // the root's vertices keep every stage they have
    double moved = 0.0;
    for (const StageRef& ref : rig.path(component)) {
      const RigStage& stage = rig.stage(ref);
      if (ref.component == 0) {
        moved *= 2.0;  // the body's stretch, 1 - z k < 2
        continue;
      }
      const double bound = bound_of(stage.param);
      moved = 2.0 * moved + std::max(stage_displacement(stage, positions[v], bound),
                                     stage_displacement(stage, positions[v], -bound));
    }
    worst = std::max(worst, moved);
  }
  return worst;
}

void LevelOptions::validate() const {
  if (levels < 1 || levels > kMaxDetailLevels) {
    throw Error(
        ErrorCode::kInvalidArgument, "levels",
        "levels: " + std::to_string(levels) + " is not 1.." + std::to_string(kMaxDetailLevels));
  }
  if (!(triangle_ratio > 0.0 && triangle_ratio < 1.0)) {
    throw Error(ErrorCode::kInvalidArgument, "triangle_ratio",
                "triangle_ratio: " + std::to_string(triangle_ratio) + " is not in (0, 1)");
  }
  for (std::size_t p = 0; p < value_bounds.size(); ++p) {
    if (!(std::isfinite(value_bounds[p]) && value_bounds[p] >= 0.0)) {
      const std::string field = "value_bounds[" + std::to_string(p) + "]";
      throw Error(ErrorCode::kInvalidArgument, field,
                  field + ": " + std::to_string(value_bounds[p]) + " is not a finite value >= 0");
    }
  }
}

DetailLevels::DetailLevels(std::vector<DetailLevel> levels,
                           std::vector<std::uint32_t> full_vertex_of)
    : levels_(std::move(levels)), full_vertex_of_(std::move(full_vertex_of)) {}

const DetailLevel& DetailLevels::level(std::size_t k) const {
  if (k >= levels_.size()) {
    throw Error(
        ErrorCode::kInvalidArgument, "level",
        "level: " + std::to_string(k) + " of " + std::to_string(levels_.size()) + " levels");
  }
  return levels_[k];
}

DetailLevels make_detail_levels(const RiggedMesh& full, const LevelOptions& options) {
  options.validate();
  if (!options.value_bounds.empty()) check_bound_count(full.rig(), options.value_bounds);
  const Mesh& mesh = full.mesh();
  // The cascade: each level from the one before, its error the sum of the steps'.
  std::vector<std::vector<std::uint32_t>> indices{mesh.indices};
  std::vector<double> errors{0.0};
  const double scale =
      meshopt_simplifyScale(&mesh.positions[0].x, mesh.vertex_count(), sizeof(glm::vec3));
  for (std::size_t k = 1; k < options.levels; ++k) {
    const std::vector<std::uint32_t>& finer = indices.back();
    // Of the two steps, the one that reaches the reduction with the smaller error and
    // keeps every fin (the component-wise one's locked borders stall coarse levels;
    // measured on the bundled fish in docs/levels-of-detail.md).
    auto [coarser, relative_error] = simplify_step(full, finer, options.triangle_ratio);
    auto [whole, whole_error] = whole_mesh_step(full, finer, options.triangle_ratio);
    if (reduces(finer, whole) && keeps_every_part(full, finer, whole) &&
        (!reduces(finer, coarser) || whole_error < relative_error)) {
      coarser = std::move(whole);
      relative_error = whole_error;
    }
    const std::size_t kept = coarser.size() / 3;
    if (!reduces(finer, coarser)) {
      throw Error(
          ErrorCode::kInvalidArgument, "levels",
          "levels: level " + std::to_string(k) + " keeps " + std::to_string(kept) + " of " +
              std::to_string(finer.size() / 3) + " triangles (target " +
              std::to_string(std::llround(double(finer.size() / 3) * options.triangle_ratio)) +
              "): the mesh is too small or all border for " + std::to_string(options.levels) +
              " levels");
    }
    errors.push_back(errors.back() + double(relative_error) * scale);
    indices.push_back(std::move(coarser));
  }
  // One vertex order: first use over the levels from the coarsest, then the vertices
  // no triangle uses; level k's vertices are those placed up to its own triangles.
  const std::size_t vertex_count = mesh.vertex_count();
  std::vector<std::uint32_t> new_of(vertex_count, kUnplaced);
  std::vector<std::uint32_t> full_of;
  full_of.reserve(vertex_count);
  std::vector<std::size_t> prefix(options.levels);
  for (std::size_t k = options.levels; k-- > 0;) {
    for (std::uint32_t v : indices[k]) {
      if (new_of[v] != kUnplaced) continue;
      new_of[v] = std::uint32_t(full_of.size());
      full_of.push_back(v);
    }
    prefix[k] = full_of.size();
  }
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    if (new_of[v] != kUnplaced) continue;
    new_of[v] = std::uint32_t(full_of.size());
    full_of.push_back(v);
  }
  prefix[0] = vertex_count;
  std::vector<DetailLevel> levels;
  for (std::size_t k = 0; k < options.levels; ++k) {
    levels.push_back(DetailLevel{level_model(full, new_of, full_of, prefix[k], indices[k], k == 0),
                                 prefix[k], indices[k].size() / 3, errors[k], false});
  }
  // Each level's error: the cascade's estimate, or the measured distance between its
  // surface and the full mesh's where that is larger, and never below a finer level's.
  const detail::SurfaceView finest{&levels.front().model.mesh().positions,
                                   &levels.front().model.mesh().indices};
  for (std::size_t k = 1; k < levels.size(); ++k) {
    const Mesh& coarse = levels[k].model.mesh();
    const double measured = detail::surface_distance({&coarse.positions, &coarse.indices}, finest);
    levels[k].geometric_error =
        std::max({levels[k].geometric_error, measured, levels[k - 1].geometric_error});
  }
  if (options.freeze_fins && has_stages_below_root(full.rig())) {
    levels.push_back(frozen_level(levels.back(), options.value_bounds));
  }
  return DetailLevels(std::move(levels), std::move(full_of));
}

}  // namespace finflex

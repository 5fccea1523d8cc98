// Shorthands for the tests: a job on either backend in one call, and the largest
// difference between two batches.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "finflex/finflex.hpp"

namespace finflex::test {

// Parameters of `model` for instances given as rows (values_per_instance() floats
// each, packed): e.g. {m0, m1, m2} for the whole-body bend.
RigParameters values_of(const RiggedMesh& model, const std::vector<float>& rows);

// Expects two device results to hold the same bits: positions, normals and tangents.
void expect_same_outputs(const DeformedBatch<float>& got, const DeformedBatch<float>& want);

// The nearest IEEE half to `value` (ties to even), as bits, from the format's
// definition. Values in [-1, 1].
std::uint16_t nearest_half(float value);

// Enqueues `values` on `batch` (with world `placements`, one per instance, or none)
// and reads the batch back.
DeformedBatch<float> run_on_device(ClDeformer& deformer, DeviceBatch& batch,
                                   const RigParameters& values, NormalMode normals,
                                   RigPath path = RigPath::kAuto, bool clamp = false,
                                   const Placement* placements = nullptr);
// The same on a new batch of the deformer's, normals in `format`.
DeformedBatch<float> run_on_device(ClDeformer& deformer, const RigParameters& values,
                                   NormalMode normals, RigPath path = RigPath::kAuto,
                                   bool clamp = false, NormalFormat format = NormalFormat::kFloat32,
                                   const Placement* placements = nullptr);

// The whole-body bend in the limits of its m: fractions of the limit for each instance.
RigParameters bend_fractions(const RiggedMesh& model, const std::vector<double>& fractions);

// The limit of the whole-body bend's m.
double bend_limit(const RiggedMesh& model);

// Every parameter of every instance at `fraction` of its limit, alternate parameters
// with opposite signs, then clamped as the backends clamp (so a fraction of 1 gives
// the values the backends use at the limits).
RigParameters at_fractions_of_the_limits(const RiggedMesh& model,
                                         const std::vector<double>& fractions);

// The limit parameter `parameter` of `rig` (resolved on `mesh`) must have, computed
// here from the stages' frames and the mesh's vertices, not from RigStage::x_max or
// the registry: the tightest, over the stages that read it, of the bend's 0.5 / x_max
// (13), x_max the largest |x| in the stage's frame of the vertices of its component
// and its descendants, and the hinge's pi.
double expected_limit(const Mesh& mesh, const Rig& rig, std::size_t parameter);

// Enqueues a copy of `from`'s outputs (positions, normals, tangents) into `to`, on the
// context's queue: a frame's outputs kept aside while later frames overwrite `from`.
void enqueue_copy(Context& context, const DeviceBatch& from, DeviceBatch& to);

// The largest difference between two batches of the same model, over every vertex
// and instance: positions (mesh units), normals and tangents (|difference| of unit
// vectors). Both batches must have tangents or neither.
struct Difference {
  double position = 0.0;
  double normal = 0.0;
  double tangent = 0.0;
  bool tangents_compared = false;
};

template <typename A, typename B>
Difference max_difference(const A& a, const B& b, std::size_t vertices, std::size_t instances) {
  Difference d;
  d.tangents_compared = a.shape.tangents && b.shape.tangents;
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      d.position = std::max(
          d.position, glm::length(glm::dvec3(a.position(i, v)) - glm::dvec3(b.position(i, v))));
      d.normal =
          std::max(d.normal, glm::length(glm::dvec3(a.normal(i, v)) - glm::dvec3(b.normal(i, v))));
      if (d.tangents_compared) {
        d.tangent = std::max(
            d.tangent, glm::length(glm::dvec3(a.tangent(i, v)) - glm::dvec3(b.tangent(i, v))));
      }
    }
  }
  return d;
}

}  // namespace finflex::test

// Shorthands for the tests: a job on either backend in one call.
#pragma once

#include <vector>

#include "finflex/finflex.hpp"

namespace finflex::test {

// Parameters of `model` for instances given as rows (values_per_instance() floats
// each, packed): e.g. {m0, m1, m2} for the whole-body bend.
RigParameters values_of(const RiggedMesh& model, const std::vector<float>& rows);

// Enqueues `values` on `batch` and reads the batch back.
DeformedBatch<float> run_on_device(ClDeformer& deformer, DeviceBatch& batch,
                                   const RigParameters& values, NormalMode normals,
                                   RigPath path = RigPath::kAuto, bool clamp = false);
// The same on a new batch of the deformer's, normals in `format`.
DeformedBatch<float> run_on_device(ClDeformer& deformer, const RigParameters& values,
                                   NormalMode normals, RigPath path = RigPath::kAuto,
                                   bool clamp = false,
                                   NormalFormat format = NormalFormat::kFloat32);

// The whole-body bend in the limits of its m: fractions of the limit for each instance.
RigParameters bend_fractions(const RiggedMesh& model, const std::vector<double>& fractions);

// The limit of the whole-body bend's m.
double bend_limit(const RiggedMesh& model);

}  // namespace finflex::test

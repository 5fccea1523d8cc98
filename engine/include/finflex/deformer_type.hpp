// The deformer registry: one description per deformer kind (the paper's bend, the
// hinge, ...), read by the rig file parser, the resolver, the parameter checks, the
// OpenCL program generator, the CPU reference and the command-line tool.
//
// Every deformer is a secant-surface transform (METHOD.md section 4): in its stage's
// local frame it maps the secant plane z = 0 onto a surface f(x, y) = (X(x), y, Z(x))
// whose spine keeps its arc length, and moves the vertex by (7) p' = f(x, y) + z n,
// its normal by (8) or by the Jacobian. A deformer only says what the surface is at x:
// the rest (frames, normals, tangents, the hierarchy) is shared.
//
// Adding a deformer: its OpenCL function in kernels/deformers/<name>.cl, its
// description (this struct) in engine/src/rig/deformers/<name>.cpp, and one line in
// engine/src/rig/deformers/registry.cpp. docs/architecture.md walks through it.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "finflex/export.hpp"

namespace finflex {

// The secant surface at one x of the spine, in the stage's frame (the spine is the
// curve f(x, 0)); y passes through unchanged (df/dy = e_y).
struct SecantSample {
  glm::dvec3 f{0.0};  // f(x, 0)
  glm::dvec3 df_dx{1.0, 0.0, 0.0};
  glm::dvec3 n{0.0, 0.0, 1.0};  // unit normal of the surface (17)
  glm::dvec3 dn_dx{0.0};        // for the Jacobian (METHOD.md section 6)
  double curvature = 0.0;       // k = theta'(x) of the spine: folds where z k >= 1
  // True where float32 arithmetic cannot follow the surface closely (the exact bend's
  // slope at its range limit): accuracy checks widen their bounds there.
  bool near_limit = false;
};

// Options a stage of a deformer takes in a rig file ("mode", "width"), each a number
// or a choice among names. Values are stored as doubles (a choice as its index).
struct DeformerOption {
  const char* key = "";              // e.g. "width"
  std::vector<const char*> choices;  // a choice among these names; empty: a number
  double minimum = 0.0;              // numbers: the inclusive range
  double maximum = 0.0;
  bool integer = false;        // numbers: whole numbers only
  double default_value = 0.0;  // used when the rig file omits the key
  const char* meaning = "";    // for messages and docs: "the hinge's width in x"
};

constexpr std::size_t kMaxStageOptions = 4;
// A stage's option values, in the order of DeformerType::options.
using StageOptions = std::array<double, kMaxStageOptions>;

// Where a stage's rest vertices (its component's and its descendants') lie in its
// frame, measured once when the rig is resolved against a mesh.
struct StageGeometry {
  double x_lowest = 0.0;   // the smallest x
  double x_highest = 0.0;  // the largest x
  double x_max = 0.0;      // the largest |x|: the bend's range (13)
  // What DeformerType::measure found (e.g. a spine's per-segment extents in z).
  std::vector<double> measurements;
};

// Values a deformer precomputes per stage for its OpenCL function (kernels read them
// from the stage table, e.g. a hinge's 1 / width, so no division runs per vertex).
constexpr std::size_t kStageConstants = 4;
using StageConstants = std::array<double, kStageConstants>;

struct DeformerType {
  const char* name = "";           // in rig files: {"deformer": "<name>"}
  const char* summary = "";        // one line, e.g. "the paper's fish bend z = m x^2 (12)"
  const char* value_meaning = "";  // what its per-instance values are, e.g. "m (12)"
  std::vector<DeformerOption> options;

  // Per-instance values one stage reads (1 for a bend's m; more for a table).
  std::size_t (*value_count)(const StageOptions& options) = nullptr;
  // The largest |value| accepted for the stage (the bend: 0.5 / x_max, (13)).
  double (*value_limit)(const StageOptions& options, const StageGeometry& geometry) = nullptr;
  // The surface at x for the stage's values (value_count of them), in double
  // precision: the CPU reference's definition of the deformer.
  SecantSample (*secant)(double x, const double* values, const StageOptions& options,
                         const StageGeometry& geometry) = nullptr;

  // OpenCL: the file under kernels/ that defines the deformer, and the function that
  // gives a stage's secant surface at a vertex in its frame, `SecantSample
  // <function>(Vec3 p, StageFrame f, __global const float* values, __global const
  // float* derived)` (kernels/common/stage_frame.cl; the shared code applies it).
  const char* cl_file = "";
  const char* (*cl_function)(const StageOptions& options) = nullptr;
  // The stage table's constants for the OpenCL function (zeros when it needs none).
  StageConstants (*stage_constants)(const StageOptions& options,
                                    const StageGeometry& geometry) = nullptr;

  // ---- Optional ----
  // Values the OpenCL function needs that follow from an instance's values but would
  // cost every vertex to compute (a spine's running integrals): `derived_count` of
  // them per stage and instance, written each frame before the deformation kernels
  // by `void <cl_prepare_function>(__global const float* values, __global float*
  // derived, StageFrame f, __local float* scratch, int item)`, called by each of the
  // instance's FF_PREPARE_ITEMS work-items (1 on CPUs, a work-group of 64 on GPUs;
  // `item` is the caller's place): scratch holds 2 FF_PREPARE_ITEMS + 2 floats of the
  // instance's, shared between FF_PREPARE_BARRIER()s, the first before any write
  // (kernels/rig.cl). Each stage's derived values
  // start 32-byte aligned (counts are rounded up to 8 floats), so a deformer may read
  // records of 4 or 8 floats as vectors.
  std::size_t (*derived_count)(const StageOptions& options) = nullptr;
  const char* cl_prepare_function = nullptr;
  // The OpenCL function for vertices that come to the stage straight from the rest
  // planes (the stage is first on their path), when it can do better there; same
  // signature as cl_function's. A component's slots are sorted by x in the frame of the
  // first stage on its path that has derived values, padding included
  // (detail::make_slot_layout), so there the lanes of a CPU work-item hold ascending x
  // (the spine takes its lanes' segments from the first and the last lane).
  const char* cl_rest_function = nullptr;
  // Measures the stage's rest vertices (in its frame) once, for value checks beyond
  // the range (StageGeometry::measurements).
  std::vector<double> (*measure)(const StageOptions& options,
                                 const std::vector<glm::dvec3>& local_positions) = nullptr;
  // Checks one instance's values beyond their range (a spine that would fold the
  // surface through itself, METHOD.md section 6). Returns an empty string when they are
  // fine; otherwise, with `clamp`, adjusts `values` so they are and returns empty; else
  // returns what is wrong ("segment 12: curvature 11.2 folds vertices 0.11 off the
  // spine (z k = 1.23 >= 1)").
  std::string (*check_values)(float* values, const StageOptions& options,
                              const StageGeometry& geometry, bool clamp) = nullptr;
  // With a rest function: the stage's constants are a table's (first x, 1 / spacing,
  // spacing, last sample), and the rest function of CPU kernels may read the segments
  // of each 8 rest slots from the generated `ff_slot_segments` (the spine,
  // kernels/deformers/spine.cl), which the rig program computes once from the rest
  // planes instead of every frame.
  bool rest_segments = false;
  // With rest_segments: the OpenCL function for vertices that reach the stage after one
  // stage of one value moved them (a fin's hinge before the body's spine), `SecantSample
  // <function>(Vec3 p, StageFrame f, __global const float* values, __global const float*
  // derived, float moved_by, int first_entry, float limit, float bins_per_unit)`:
  // `moved_by` the earlier stage's value, and where the generated `ff_swept_segments`
  // holds the segments the work-item's lanes reach for it (the spine,
  // kernels/deformers/spine.cl spine_stage_swept).
  const char* cl_swept_function = nullptr;
};

// Every registered deformer, in registry order.
FINFLEX_API const std::vector<const DeformerType*>& deformer_types();
// The deformer of that name, or nullptr.
FINFLEX_API const DeformerType* find_deformer_type(const std::string& name);
// "\"bend\", \"hinge\" or \"spine\"": the registered names, for messages.
FINFLEX_API std::string deformer_type_names();

// The options of `type` at their defaults.
FINFLEX_API StageOptions default_options(const DeformerType& type);
// "mode exact, width 0.05": a stage's options as a rig file would write them.
FINFLEX_API std::string describe_options(const DeformerType& type, const StageOptions& options);

}  // namespace finflex

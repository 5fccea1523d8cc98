// Per-instance parameter values of a rig: instance_count rows of
// Rig::values_per_instance() floats, each parameter at its offset in the row.
//
//   RigParameters values(model, 1000);        // all zero: the rest pose
//   values.set(7, "tail_angle", 0.4f);
//   job.parameters = values.view();
//
// Thread-safety: a RigParameters is written by its thread; a job reads its values
// during enqueue() / run_reference() only (enqueue copies them), so they may be
// refilled for the next frame as soon as enqueue() returns.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "finflex/export.hpp"
#include "finflex/model.hpp"
#include "finflex/rig.hpp"

namespace finflex {

// Rows of parameter values as a job reads them, without owning them: row i (instance
// i) starts at data + i * stride and holds the rig's values_per_instance() values.
struct ParameterView {
  const float* data = nullptr;
  std::size_t instance_count = 0;
  std::size_t stride = 0;  // floats from one row to the next; 0: values_per_instance()
};

class FINFLEX_API RigParameters {
 public:
  // kInvalidArgument (field "instances") for 0 instances.
  RigParameters(const Rig& rig, std::size_t instance_count);
  RigParameters(const RiggedMesh& model, std::size_t instance_count)
      : RigParameters(model.rig(), instance_count) {}

  std::size_t instance_count() const { return instance_count_; }
  std::size_t values_per_instance() const { return values_per_instance_; }
  const std::vector<RigParameter>& parameters() const { return parameters_; }

  // Sets a one-value parameter, or every value of a table parameter, by name.
  // kInvalidArgument naming an unknown parameter (listing the rig's), an instance out
  // of range, or a count that does not match the parameter's. Values are checked
  // when a job uses them.
  void set(std::size_t instance, const std::string& name, float value);
  void set(std::size_t instance, const std::string& name, const std::vector<float>& values);
  // The first value of a parameter by index (kInvalidArgument when out of range).
  float get(std::size_t instance, std::size_t parameter) const;

  const std::vector<float>& values() const { return values_; }  // row-major
  std::vector<float>& values() { return values_; }
  ParameterView view() const { return {values_.data(), instance_count_, values_per_instance_}; }

 private:
  std::vector<RigParameter> parameters_;
  std::size_t instance_count_ = 0;
  std::size_t values_per_instance_ = 0;
  std::vector<float> values_;

  std::size_t index_of(const std::string& name) const;
  void check_instance(std::size_t instance) const;
};

// Checks every value of `view` against the rig's parameters: NaN or infinite values
// are kInvalidArgument, |value| above the parameter's limit kOutOfRange (unless
// `clamp`, which clamps it into the range), each naming the value as
// "name[instance]" (a table's as "name[instance][k]"), the value and the range. The
// checked (and clamped) values are written to `out`, rows packed
// (values_per_instance() apart); on error `out` holds an unspecified prefix.
FINFLEX_API void check_parameters(const Rig& rig, const ParameterView& view, bool clamp,
                                  float* out);

}  // namespace finflex

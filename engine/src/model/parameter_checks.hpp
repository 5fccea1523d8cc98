// The per-frame parameter checks (check_parameters of finflex/parameters.hpp) with
// their bounds prepared once per rig: one vectorisable pass copies the values and
// tells whether every one is finite and within its bound; only when it says no are
// the values walked again, to clamp them or to name the bad one.
#pragma once

#include <cstddef>
#include <vector>

#include "finflex/parameters.hpp"
#include "finflex/rig.hpp"

namespace finflex::detail {

class ParameterChecker {
 public:
  explicit ParameterChecker(const Rig& rig);

  // check_parameters(rig, view, clamp, out), `out` holding values_per_instance() *
  // view.instance_count floats.
  void check(const ParameterView& view, bool clamp, float* out) const;
  // The same checks without writing anything (no clamping).
  void check(const ParameterView& view, bool clamp) const;

 private:
  // A stage whose deformer checks its values beyond their range (check_values).
  struct StageCheck {
    RigStage stage;
    std::string where;  // "the spine of 'body'"
  };

  std::vector<RigParameter> parameters_;
  std::size_t values_per_instance_ = 0;
  std::vector<float> tile_;  // each value's accepted |value|, rows repeated to 16 lanes
  std::vector<StageCheck> stage_checks_;

  void check_slowly(const ParameterView& view, bool clamp, float* out) const;
  void check_stages(const ParameterView& view, bool clamp, float* out) const;
};

}  // namespace finflex::detail

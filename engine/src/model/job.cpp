// Names of the job's settings (finflex/job.hpp).
#include "finflex/job.hpp"

namespace finflex {

const char* to_string(NormalMode mode) {
  return mode == NormalMode::kJacobian ? "jacobian" : "rotate";
}

NormalMode parse_normal_mode(const std::string& text, const std::string& field) {
  if (text == "rotate") return NormalMode::kRotate;
  if (text == "jacobian") return NormalMode::kJacobian;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not a normal mode (expected rotate or jacobian)");
}

const char* to_string(RigPath path) {
  switch (path) {
    case RigPath::kAuto:
      return "auto";
    case RigPath::kFused:
      return "fused";
    case RigPath::kPasses:
      return "passes";
  }
  return "auto";
}

RigPath parse_rig_path(const std::string& text, const std::string& field) {
  if (text == "auto") return RigPath::kAuto;
  if (text == "fused") return RigPath::kFused;
  if (text == "passes") return RigPath::kPasses;
  throw Error(ErrorCode::kInvalidArgument, field,
              field + " '" + text + "' is not an execution path (expected auto, fused or passes)");
}

}  // namespace finflex

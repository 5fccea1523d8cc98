// The C job's enums as the library's.
#include "job.hpp"

#include <string>

namespace finflex::c {

finflex::NormalMode normal_mode(finflex_normal_mode mode) {
  switch (mode) {
    case FINFLEX_NORMALS_ROTATE:
      return NormalMode::kRotate;
    case FINFLEX_NORMALS_JACOBIAN:
      return NormalMode::kJacobian;
    default:  // not a value of the enum: refused below
      break;
  }
  throw Error(ErrorCode::kInvalidArgument, "job.normals",
              "job.normals = " + std::to_string(static_cast<int>(mode)) +
                  ": expected FINFLEX_NORMALS_ROTATE (0) or FINFLEX_NORMALS_JACOBIAN (1)");
}

finflex::RigPath rig_path(finflex_rig_path path) {
  switch (path) {
    case FINFLEX_PATH_AUTO:
      return RigPath::kAuto;
    case FINFLEX_PATH_FUSED:
      return RigPath::kFused;
    case FINFLEX_PATH_PASSES:
      return RigPath::kPasses;
    default:  // not a value of the enum: refused below
      break;
  }
  throw Error(ErrorCode::kInvalidArgument, "job.path",
              "job.path = " + std::to_string(static_cast<int>(path)) +
                  ": expected FINFLEX_PATH_AUTO (0), FINFLEX_PATH_FUSED (1) or "
                  "FINFLEX_PATH_PASSES (2)");
}

std::vector<cl::Event> wait_events(finflex_event* const* wait, std::size_t count) {
  std::vector<cl::Event> events;
  if (count == 0) return events;
  require(wait, "wait");
  for (std::size_t k = 0; k < count; ++k) {
    const std::string name = "wait[" + std::to_string(k) + "]";
    events.push_back(require(wait[k], name.c_str())->event);
  }
  return events;
}

}  // namespace finflex::c

#include "finflex/error.hpp"

namespace finflex {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return "invalid_argument";
    case ErrorCode::kOutOfRange:
      return "out_of_range";
    case ErrorCode::kInvalidMesh:
      return "invalid_mesh";
    case ErrorCode::kIo:
      return "io";
    case ErrorCode::kFormat:
      return "format";
    case ErrorCode::kDevice:
      return "device";
    case ErrorCode::kOpenCL:
      return "opencl";
  }
  return "unknown";
}

Error::Error(ErrorCode code, std::string field, const std::string& message)
    : std::runtime_error(message), code_(code), field_(std::move(field)) {}

}  // namespace finflex

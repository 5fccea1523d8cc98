// FinFlex error type: one exception class carrying a code, the offending field and a
// message that names the field and its value.
#pragma once

#include <stdexcept>
#include <string>

#include "finflex/export.hpp"

namespace finflex {

enum class ErrorCode {
  kInvalidArgument,  // a value outside its documented domain (NaN, negative count, ...)
  kOutOfRange,       // a deformation parameter outside its valid range (e.g. |m| > 0.5 / x_max)
  kInvalidMesh,      // empty, inconsistent or non-finite mesh data
  kIo,               // a file could not be read or written
  kFormat,           // a file could be read but its content is not a supported mesh
  kDevice,           // no OpenCL platform / device, or the named device does not exist
  kOpenCL,           // an OpenCL call failed (build log or status in the message)
};

// Returns a short stable name for `code`, e.g. "out_of_range".
FINFLEX_API const char* error_code_name(ErrorCode code);

class FINFLEX_API Error : public std::runtime_error {
 public:
  // `field` names the input at fault ("m", "instances", "positions[12].x", "--in").
  Error(ErrorCode code, std::string field, const std::string& message);

  ErrorCode code() const { return code_; }
  const std::string& field() const { return field_; }

 private:
  ErrorCode code_;
  std::string field_;
};

}  // namespace finflex

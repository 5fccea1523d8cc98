// Status names, the error records and the library's version.
#include <new>

#include "handles.hpp"

namespace finflex::c {

finflex_error& thread_error() {
  thread_local finflex_error error;
  return error;
}

finflex_status fail(finflex_error* slot, finflex_status status, std::string field,
                    std::string message) {
  finflex_error& thread = thread_error();
  thread.status = status;
  thread.field = std::move(field);
  thread.message = std::move(message);
  if (slot != nullptr) *slot = thread;
  return status;
}

finflex_status status_of(finflex::ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return FINFLEX_ERROR_INVALID_ARGUMENT;
    case ErrorCode::kOutOfRange:
      return FINFLEX_ERROR_OUT_OF_RANGE;
    case ErrorCode::kInvalidMesh:
      return FINFLEX_ERROR_INVALID_MESH;
    case ErrorCode::kIo:
      return FINFLEX_ERROR_IO;
    case ErrorCode::kFormat:
      return FINFLEX_ERROR_FORMAT;
    case ErrorCode::kDevice:
      return FINFLEX_ERROR_DEVICE;
    case ErrorCode::kOpenCL:
      return FINFLEX_ERROR_OPENCL;
  }
  return FINFLEX_ERROR_INTERNAL;
}

}  // namespace finflex::c

extern "C" {

const char* finflex_status_name(finflex_status status) {
  switch (status) {
    case FINFLEX_OK:
      return "ok";
    case FINFLEX_ERROR_INVALID_ARGUMENT:
      return finflex::error_code_name(finflex::ErrorCode::kInvalidArgument);
    case FINFLEX_ERROR_OUT_OF_RANGE:
      return finflex::error_code_name(finflex::ErrorCode::kOutOfRange);
    case FINFLEX_ERROR_INVALID_MESH:
      return finflex::error_code_name(finflex::ErrorCode::kInvalidMesh);
    case FINFLEX_ERROR_IO:
      return finflex::error_code_name(finflex::ErrorCode::kIo);
    case FINFLEX_ERROR_FORMAT:
      return finflex::error_code_name(finflex::ErrorCode::kFormat);
    case FINFLEX_ERROR_DEVICE:
      return finflex::error_code_name(finflex::ErrorCode::kDevice);
    case FINFLEX_ERROR_OPENCL:
      return finflex::error_code_name(finflex::ErrorCode::kOpenCL);
    case FINFLEX_ERROR_OUT_OF_MEMORY:
      return "out_of_memory";
    case FINFLEX_ERROR_INTERNAL:
      return "internal";
    case FINFLEX_STATUS_MAX_ENUM:
      break;
  }
  return "unknown";
}

const char* finflex_version(void) { return FINFLEX_C_VERSION; }

const finflex_error* finflex_last_error(void) { return &finflex::c::thread_error(); }

finflex_status finflex_error_status(const finflex_error* error) {
  return error == nullptr ? FINFLEX_OK : error->status;
}
const char* finflex_error_message(const finflex_error* error) {
  return error == nullptr ? "" : error->message.c_str();
}
const char* finflex_error_field(const finflex_error* error) {
  return error == nullptr ? "" : error->field.c_str();
}

}  // extern "C"

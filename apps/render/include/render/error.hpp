// The renderer's one error type: a code, the name of the offending field, and a
// one-line message (no newlines, so a command-line tool can print it as it is).
#pragma once

#include <stdexcept>
#include <string>

namespace finflex::render {

enum class ErrorCode {
  kNoDevice,         // no EGL device or display could be initialised, or no GL 3.3 context
  kGraphics,         // the GL driver refused something (shader, framebuffer, limit)
  kInvalidArgument,  // a bad camera, scene, mesh, stream or image
  kIo,               // a file or a child process (ffmpeg) failed
};

const char* to_string(ErrorCode code);

class RenderError : public std::runtime_error {
 public:
  // Newlines in `message` become " | ".
  RenderError(ErrorCode code, std::string field, const std::string& message);

  ErrorCode code() const { return code_; }
  const std::string& field() const { return field_; }

 private:
  ErrorCode code_;
  std::string field_;
};

}  // namespace finflex::render

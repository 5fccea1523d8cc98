#include "render/error.hpp"

#include <utility>

namespace finflex::render {

namespace {

std::string one_line(const std::string& message) {
  std::string line;
  line.reserve(message.size());
  for (std::size_t i = 0; i < message.size(); ++i) {
    const char c = message[i];
    if (c == '\r') continue;
    if (c == '\n') {
      if (i + 1 < message.size()) line += " | ";
      continue;
    }
    line += c;
  }
  return line;
}

}  // namespace

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::kNoDevice:
      return "no_device";
    case ErrorCode::kGraphics:
      return "graphics";
    case ErrorCode::kInvalidArgument:
      return "invalid_argument";
    case ErrorCode::kIo:
      return "io";
  }
  return "unknown";
}

RenderError::RenderError(ErrorCode code, std::string field, const std::string& message)
    : std::runtime_error(one_line(message)), code_(code), field_(std::move(field)) {}

}  // namespace finflex::render

// Strict text scanning for the mesh readers (see mesh_io_text.hpp).
#include "io/text.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

namespace finflex::io {

bool LineReader::next(TextLine& line) {
  if (position_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', position_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  std::string_view text = text_.substr(position_, stop - position_);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  position_ = end == std::string_view::npos ? text_.size() : end + 1;
  line.number = ++number_;
  line.text = text;
  return true;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

std::string_view strip_comment(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '#' && (i == 0 || is_blank(line[i - 1]))) return line.substr(0, i);
  }
  return line;
}

void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
}

std::string printable(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  if (text.size() > kMaxShown) out += "...";
  return out;
}

std::string shown(std::string_view token) { return "'" + printable(token) + "'"; }

std::string line_field(std::size_t number) { return "line " + std::to_string(number); }

namespace {

// `token` without a leading '+' (std::from_chars takes none); empty if what follows
// the '+' is another sign or nothing.
std::string_view without_plus(std::string_view token) {
  if (token.empty() || token.front() != '+') return token;
  token.remove_prefix(1);
  if (token.empty() || token.front() == '+' || token.front() == '-') return {};
  return token;
}

}  // namespace

NumberError narrow_to_float(double value, float& narrowed) {
  if (!std::isfinite(value)) return NumberError::kNotFinite;
  constexpr double kMax = std::numeric_limits<float>::max();
  // Values below FLT_MAX + half an ulp (2^128 - 2^103) round to FLT_MAX.
  constexpr double kRoundsToMax = 340282356779733661637539395458142568448.0;
  const double magnitude = std::fabs(value);
  if (magnitude >= kRoundsToMax) return NumberError::kOutOfRange;
  narrowed =
      magnitude > kMax ? static_cast<float>(std::copysign(kMax, value)) : static_cast<float>(value);
  return NumberError::kNone;
}

NumberError parse_double(std::string_view token, double& value) {
  const std::string_view digits = without_plus(token);
  if (digits.empty()) return NumberError::kUnreadable;
  const char* const last = digits.data() + digits.size();
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), last, parsed);
  if (error == std::errc::invalid_argument || end != last) return NumberError::kUnreadable;
  if (error == std::errc::result_out_of_range) return NumberError::kOutOfRange;
  if (!std::isfinite(parsed)) return NumberError::kNotFinite;
  value = parsed;
  return NumberError::kNone;
}

NumberError parse_float(std::string_view token, float& value) {
  const std::string_view digits = without_plus(token);
  if (digits.empty()) return NumberError::kUnreadable;
  const char* const last = digits.data() + digits.size();
  float parsed = 0.0f;
  const auto [end, error] = std::from_chars(digits.data(), last, parsed);
  if (error == std::errc::invalid_argument || end != last) return NumberError::kUnreadable;
  if (error == std::errc::result_out_of_range) {
    // Underflow (rounds to 0 or a subnormal) and the few numbers just above FLT_MAX
    // that round to it are fine; through double, which holds both exactly enough.
    double wide = 0.0;
    const auto [wide_end, wide_error] = std::from_chars(digits.data(), last, wide);
    if (wide_error != std::errc() || wide_end != last) return NumberError::kOutOfRange;
    return narrow_to_float(wide, value);
  }
  if (!std::isfinite(parsed)) return NumberError::kNotFinite;
  value = parsed;
  return NumberError::kNone;
}

NumberError parse_int(std::string_view token, std::int64_t& value) {
  const std::string_view digits = without_plus(token);
  if (digits.empty()) return NumberError::kUnreadable;
  const char* const last = digits.data() + digits.size();
  std::int64_t parsed = 0;
  const auto [end, error] = std::from_chars(digits.data(), last, parsed);
  if (error == std::errc::invalid_argument || end != last) return NumberError::kUnreadable;
  if (error == std::errc::result_out_of_range) return NumberError::kOutOfRange;
  value = parsed;
  return NumberError::kNone;
}

void throw_at(ErrorCode code, const std::string& where, const std::string& message) {
  throw Error(code, where, where + ": " + message);
}

void throw_float_error(NumberError error, std::string_view token, const std::string& where,
                       const std::string& what) {
  const std::string value = what + " " + shown(token);
  switch (error) {
    case NumberError::kNotFinite:
      throw_at(ErrorCode::kInvalidMesh, where, value + " is not finite");
    case NumberError::kOutOfRange:
      throw_at(ErrorCode::kInvalidMesh, where, value + " is outside the float range");
    default:
      throw_at(ErrorCode::kFormat, where, value + " is not a number");
  }
}

float read_float(std::string_view token, const std::string& where, const std::string& what) {
  float value = 0.0f;
  const NumberError error = parse_float(token, value);
  if (error != NumberError::kNone) throw_float_error(error, token, where, what);
  return value;
}

std::int64_t read_int(std::string_view token, const std::string& where, const std::string& what) {
  std::int64_t value = 0;
  switch (parse_int(token, value)) {
    case NumberError::kNone:
      return value;
    case NumberError::kOutOfRange:
      throw_at(ErrorCode::kInvalidMesh, where, what + " " + shown(token) + " is out of range");
    default:
      throw_at(ErrorCode::kFormat, where, what + " " + shown(token) + " is not an integer");
  }
}

}  // namespace finflex::io

#include "arguments.hpp"

#include <cctype>
#include <cmath>
#include <limits>

#include "cli_errors.hpp"
#include "finflex/error.hpp"

namespace finflex::cli {
namespace {

[[noreturn]] void fail(const std::string& option, const std::string& text,
                       const std::string& expected) {
  throw Error(ErrorCode::kInvalidArgument, option, option + " '" + text + "' is not " + expected);
}

}  // namespace

std::uint64_t parse_count(const std::string& text, const std::string& option, std::uint64_t minimum,
                          std::uint64_t maximum) {
  const std::string expected =
      "a whole number in [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]";
  if (text.empty() || text.size() > 20) fail(option, text, expected);
  std::uint64_t value = 0;
  for (char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) fail(option, text, expected);
    const std::uint64_t digit = static_cast<std::uint64_t>(c - '0');
    if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) {
      fail(option, text, expected);
    }
    value = value * 10 + digit;
  }
  if (value < minimum || value > maximum) fail(option, text, expected);
  return value;
}

double parse_positive(const std::string& text, const std::string& option, bool zero_allowed) {
  const double value = parse_number(text, option);
  if (!std::isfinite(value) || value < 0.0 || (!zero_allowed && value == 0.0)) {
    fail(option, text, zero_allowed ? "a finite number >= 0" : "a finite number > 0");
  }
  return value;
}

std::pair<double, double> parse_positive_pair(const std::string& text, const std::string& option) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) fail(option, text, "two numbers A,B");
  return {parse_positive(text.substr(0, comma), option),
          parse_positive(text.substr(comma + 1), option)};
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  const std::string expected = "WIDTHxHEIGHT, each a whole number in [1, 16384]";
  const std::size_t x = text.find('x');
  if (x == std::string::npos) fail(option, text, expected);
  try {
    const auto width = static_cast<int>(parse_count(text.substr(0, x), option, 1, 16384));
    const auto height = static_cast<int>(parse_count(text.substr(x + 1), option, 1, 16384));
    return {width, height};
  } catch (const Error&) {
    fail(option, text, expected);
  }
}

}  // namespace finflex::cli

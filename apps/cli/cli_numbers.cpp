#include "cli_numbers.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "finflex/error.hpp"

namespace finflex::cli {

std::size_t parse_count(const std::string& text, const std::string& option, std::size_t minimum,
                        std::size_t maximum, const std::string& why) {
  const std::string range = "[" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]";
  const std::string quoted = option + " '" + text + "'";
  bool digits = !text.empty();
  for (const char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  if (!digits) {
    throw Error(ErrorCode::kInvalidArgument, option,
                quoted + ": expected a whole number in " + range);
  }
  std::size_t value = 0;
  for (const char c : text) {
    const std::size_t digit = static_cast<std::size_t>(c - '0');
    // value * 10 + digit > maximum, without overflow: value * 10 <= maximum first.
    if (value > maximum / 10 || digit > maximum - value * 10) {
      throw Error(ErrorCode::kOutOfRange, option,
                  quoted + " is above the limit " + std::to_string(maximum) +
                      (why.empty() ? std::string() : " (" + why + ")"));
    }
    value = value * 10 + digit;
  }
  if (value < minimum) {
    throw Error(ErrorCode::kInvalidArgument, option,
                quoted + ": expected a whole number in " + range);
  }
  return value;
}

double parse_number(const std::string& text, const std::string& option) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) ||
      end != begin + text.size()) {
    throw Error(ErrorCode::kInvalidArgument, option, option + " '" + text + "' is not a number");
  }
  return value;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

double parse_in_range(const std::string& text, const std::string& option, double low, double high,
                      const std::string& unit) {
  const double value = parse_number(text, option);
  if (!(value >= low && value <= high)) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " " + text + ": " + std::to_string(int(low)) + " to " +
                    std::to_string(int(high)) + " " + unit + " expected");
  }
  return value;
}

std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      std::size_t count) {
  std::vector<double> out;
  for (const std::string& part : split_list(text)) {
    double value = 0.0;
    try {
      value = parse_number(part, option);
    } catch (const Error&) {
      value = std::nan("");  // named below, with the whole list
    }
    if (!std::isfinite(value)) {
      throw Error(ErrorCode::kInvalidArgument, option,
                  option + " '" + text + "': '" + part + "' is not a finite number");
    }
    out.push_back(value);
  }
  if (out.size() != count) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "': " + std::to_string(count) + " numbers expected, " +
                    std::to_string(out.size()) + " given");
  }
  return out;
}

double parse_positive(const std::string& text, const std::string& option, bool zero_allowed) {
  const double value = parse_number(text, option);
  if (!std::isfinite(value) || value < 0.0 || (!zero_allowed && value == 0.0)) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "' is not " +
                    (zero_allowed ? "a finite number >= 0" : "a finite number > 0"));
  }
  return value;
}

std::pair<double, double> parse_positive_pair(const std::string& text, const std::string& option) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "' is not two numbers A,B");
  }
  return {parse_positive(text.substr(0, comma), option),
          parse_positive(text.substr(comma + 1), option)};
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  const std::size_t x = text.find('x');
  try {
    if (x == std::string::npos) throw Error(ErrorCode::kInvalidArgument, option, "no x");
    const auto width = static_cast<int>(parse_count(text.substr(0, x), option, 1, 16384));
    const auto height = static_cast<int>(parse_count(text.substr(x + 1), option, 1, 16384));
    return {width, height};
  } catch (const Error&) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "' is not WIDTHxHEIGHT, each a whole number in [1, 16384]");
  }
}

}  // namespace finflex::cli

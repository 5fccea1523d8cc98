// Numbers (and words from a fixed set) on the command line, parsed strictly: the whole
// text must be the number, and a count is decimal digits only, so "-1" is an error
// naming the option and the value as typed (never 2^64 - 1), and a count past its
// limit is refused before anything is allocated or read.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::cli {

// One of `choices` (word, value) for `text`, else kInvalidArgument naming `option` and
// `what` the words name: "--draw 'some' is not a way to draw (expected all or written)".
template <typename Value>
Value parse_choice(const std::string& text, const std::string& option, const std::string& what,
                   const std::vector<std::pair<std::string, Value>>& choices,
                   const std::string& expected) {
  for (const auto& [word, value] : choices) {
    if (text == word) return value;
  }
  throw Error(ErrorCode::kInvalidArgument, option,
              option + " '" + text + "' is not " + what + " (expected " + expected + ")");
}

// A whole number in [minimum, maximum] written with decimal digits only (no sign,
// space, point or exponent). Errors (field `option`): kInvalidArgument "--frames '-1':
// expected a whole number in [1, 1000000]"; kOutOfRange when the digits are past
// `maximum`: "--frames '99999999999' is above the limit 1000000 (<why>)".
std::size_t parse_count(const std::string& text, const std::string& option, std::size_t minimum,
                        std::size_t maximum, const std::string& why = "");

// A decimal or hexadecimal floating-point number (strtod's syntax, "inf" and "nan"
// included: the library names those as errors where they are), the whole text, no
// leading space. kInvalidArgument naming `option` when the text is not a number.
double parse_number(const std::string& text, const std::string& option);

// A finite number > 0 (or >= 0 when `zero_allowed`); kInvalidArgument naming `option`.
double parse_positive(const std::string& text, const std::string& option,
                      bool zero_allowed = false);

// "A,B": two finite numbers > 0.
std::pair<double, double> parse_positive_pair(const std::string& text, const std::string& option);

// A comma-separated list's items, as typed ("" gives one empty item).
std::vector<std::string> split_list(const std::string& text);

// A finite number in [low, high]; kInvalidArgument naming `option`:
// "--turbidity -1: 0 to 100 NTU expected" (`unit` after the range).
double parse_in_range(const std::string& text, const std::string& option, double low, double high,
                      const std::string& unit);

// "A,B,...": exactly `count` finite numbers, comma-separated. kInvalidArgument naming
// `option`: "--noise '1,x': 'x' is not a finite number", or the count given.
std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      std::size_t count);

// "WIDTHxHEIGHT": an image size, each a whole number in [1, 16384] ("640x360").
std::pair<int, int> parse_size(const std::string& text, const std::string& option);

}  // namespace finflex::cli

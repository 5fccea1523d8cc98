// Strict parsing of numeric command-line values given as text: the whole text must be
// the number, in its domain, or the error names the option and the text as typed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace finflex::cli {

// A whole number in [minimum, maximum] ("-1", "1.5", "12abc", "99999999999999999999"
// are errors naming `option`).
std::uint64_t parse_count(const std::string& text, const std::string& option, std::uint64_t minimum,
                          std::uint64_t maximum);

// A finite number > 0 (or >= 0 when `zero_allowed`).
double parse_positive(const std::string& text, const std::string& option,
                      bool zero_allowed = false);

// "A,B": two finite numbers > 0.
std::pair<double, double> parse_positive_pair(const std::string& text, const std::string& option);

// "WIDTHxHEIGHT": an image size, each a whole number in [1, 16384] ("640x360").
std::pair<int, int> parse_size(const std::string& text, const std::string& option);

}  // namespace finflex::cli

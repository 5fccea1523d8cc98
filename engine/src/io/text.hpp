// Private: strict scanning of text formats, shared by the OBJ, OFF, PLY (ASCII) and
// STL (ASCII) readers. Numbers are read whole or not at all: a token is a number only
// if all of it is one, independently of the C locale.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "finflex/error.hpp"

namespace finflex::io {

// One line of a text file: its 1-based number and its text without the line end.
struct TextLine {
  std::size_t number = 0;
  std::string_view text;
};

// Reads a text line by line. A line ends at "\n" (a "\r" before it is dropped); the
// last line needs none. Work is linear in the text's length.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  // The next line, false at the end of the text.
  bool next(TextLine& line);
  // The bytes not read yet.
  std::size_t remaining() const { return text_.size() - position_; }
  // The number of the last line returned by next() (0 before the first).
  std::size_t line_number() const { return number_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  std::size_t number_ = 0;
};

// Space, tab, carriage return, vertical tab and form feed: what separates words.
bool is_blank(char c);

// `text` without blanks at either end.
std::string_view trim(std::string_view text);

// `line` up to its comment: the first '#' that starts a word (at the start of the line
// or after a blank).
std::string_view strip_comment(std::string_view line);

// The blank-separated words of `line`, into `words` (cleared first).
void split_words(std::string_view line, std::vector<std::string_view>& words);

// `text` from a file made fit for a message or a field: at most 40 characters (then
// "..."), bytes that are not printable ASCII as '?'.
std::string printable(std::string_view text);

// printable(token) in quotes.
std::string shown(std::string_view token);

// "line 12".
std::string line_field(std::size_t number);

enum class NumberError {
  kNone,
  kUnreadable,  // not a number, or more than a number
  kNotFinite,   // "nan", "inf", ...
  kOutOfRange,  // beyond the type's range (for floats: overflow; underflow rounds to 0)
};

// Decimal numbers with an optional sign ('+' or '-'), as the whole token. Floats are
// rounded to the nearest float (numbers just above FLT_MAX that round to it are
// FLT_MAX); no hexadecimal floats.
NumberError parse_float(std::string_view token, float& value);
NumberError parse_double(std::string_view token, double& value);
NumberError parse_int(std::string_view token, std::int64_t& value);

// `value` to the nearest float: kNotFinite for NaN or infinities, kOutOfRange if it
// rounds beyond FLT_MAX.
NumberError narrow_to_float(double value, float& narrowed);

// Error whose field is `where` and whose message is "<where>: <message>".
[[noreturn]] void throw_at(ErrorCode code, const std::string& where, const std::string& message);

// Throws for `error` (not kNone) about a float read from `token`: "<where>: <what>
// '<token>' is not a number" (kFormat), "... is not finite" or "... is outside the
// float range" (kInvalidMesh).
[[noreturn]] void throw_float_error(NumberError error, std::string_view token,
                                    const std::string& where, const std::string& what);

// parse_float / parse_int that throw kFormat for a token that is not a number of the
// kind, kInvalidMesh for one that is not finite or out of range.
float read_float(std::string_view token, const std::string& where, const std::string& what);
std::int64_t read_int(std::string_view token, const std::string& where, const std::string& what);

}  // namespace finflex::io

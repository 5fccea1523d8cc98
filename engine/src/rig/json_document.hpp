// The JSON document of a rig file, read with a SAX handler of our own: in one pass and
// without recursion, it refuses a key that appears twice in an object (nlohmann would
// keep the last one without a word) and arrays or objects nested deeper than
// kMaxRigJsonDepth, each naming where. (nlohmann's parser callbacks, which could do
// the same, take time quadratic in the number of values.)
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace finflex::detail {

// Errors: kFormat (field "rig") "rig: malformed JSON: <the parser's message with line
// and column>"; kInvalidArgument naming the place ("components[1].select") for a
// duplicate key or nesting past kMaxRigJsonDepth.
nlohmann::json parse_rig_document(const std::string& text);

// "path.key" ("key" at the top level) and "path[index]": the places of messages.
std::string json_member(const std::string& path, const std::string& key);
std::string json_element(const std::string& path, std::size_t index);

}  // namespace finflex::detail

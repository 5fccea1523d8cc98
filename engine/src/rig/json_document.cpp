#include "rig/json_document.hpp"

#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "finflex/error.hpp"
#include "finflex/rig.hpp"

namespace finflex::detail {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

// Builds the document as nlohmann's own DOM parser does (values are added to the
// innermost open array or object; open containers are held by pointer, and only the
// innermost one grows, so the pointers stay valid), and checks keys and depth.
class DocumentBuilder final : public nlohmann::json_sax<json> {
 public:
  bool null() override { return add(json(nullptr)); }
  bool boolean(bool value) override { return add(json(value)); }
  bool number_integer(number_integer_t value) override { return add(json(value)); }
  bool number_unsigned(number_unsigned_t value) override { return add(json(value)); }
  bool number_float(number_float_t value, const string_t& /*text*/) override {
    return add(json(value));
  }
  bool string(string_t& value) override { return add(json(std::move(value))); }
  bool binary(binary_t& value) override { return add(json::binary(std::move(value))); }

  bool start_object(std::size_t /*elements*/) override { return open(json::object(), true); }
  bool start_array(std::size_t /*elements*/) override { return open(json::array(), false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& key) override {
    Level& level = levels_.back();
    level.key = key;
    if (!level.keys.insert(key).second) {
      fail(path(),
           "duplicate key '" + key + "' (the later value would silently replace the earlier)");
    }
    next_member_ = &(*open_.back())[key];
    return true;
  }

  bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/,
                   const nlohmann::detail::exception& error) override {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ...", or
    // out_of_range.406 for a number beyond double ("number overflow parsing '1e999'").
    std::string message = error.what();
    if (const std::size_t end = message.find("] ");
        message.rfind("[json.", 0) == 0 && end != std::string::npos) {
      message.erase(0, end + 2);
    }
    throw Error(ErrorCode::kFormat, "rig", "rig: malformed JSON: " + message);
  }

  json take() { return std::move(root_); }

 private:
  struct Level {
    bool object = true;
    std::set<std::string> keys;
    std::string key;           // object: the key being parsed
    std::size_t elements = 0;  // array: elements started so far
  };

  // The place of the value being parsed, e.g. "components[1].select".
  std::string path() const {
    std::string place;
    for (const Level& l : levels_) {
      place = l.object ? json_member(place, l.key) : json_element(place, l.elements - 1);
    }
    return place;
  }

  // Puts `value` where the parser is (the root, the next array element or the member
  // whose key came last) and returns it.
  json* place(json&& value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    json& container = *open_.back();
    if (container.is_array()) {
      ++levels_.back().elements;
      container.push_back(std::move(value));
      return &container.back();
    }
    *next_member_ = std::move(value);
    return next_member_;
  }

  bool add(json&& value) {
    place(std::move(value));
    return true;
  }

  bool open(json&& container, bool object) {
    if (levels_.size() >= kMaxRigJsonDepth) {
      if (!open_.empty() && open_.back()->is_array()) ++levels_.back().elements;
      const std::string at = path();
      fail(at.empty() ? "rig" : at, "arrays and objects nested deeper than " +
                                        std::to_string(kMaxRigJsonDepth) +
                                        " levels (kMaxRigJsonDepth; a rig file needs 6)");
    }
    open_.push_back(place(std::move(container)));
    levels_.push_back(Level{object, {}, {}, 0});
    return true;
  }

  bool close() {
    open_.pop_back();
    levels_.pop_back();
    return true;
  }

  json root_;
  std::vector<json*> open_;
  std::vector<Level> levels_;
  json* next_member_ = nullptr;
};

}  // namespace

std::string json_member(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string json_element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

json parse_rig_document(const std::string& text) {
  DocumentBuilder builder;
  json::sax_parse(text, &builder);
  return builder.take();
}

}  // namespace finflex::detail

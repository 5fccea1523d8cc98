// Lookups over the deformer registry (finflex/deformer_type.hpp) and the text of a
// stage's options.
#include <sstream>

#include "finflex/deformer_type.hpp"

namespace finflex {

const DeformerType* find_deformer_type(const std::string& name) {
  for (const DeformerType* type : deformer_types()) {
    if (name == type->name) return type;
  }
  return nullptr;
}

std::string deformer_type_names() {
  const std::vector<const DeformerType*>& types = deformer_types();
  std::string names;
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (k > 0) names += k + 1 == types.size() ? " or " : ", ";
    names += "\"" + std::string(types[k]->name) + "\"";
  }
  return names;
}

StageOptions default_options(const DeformerType& type) {
  StageOptions options{};
  for (std::size_t k = 0; k < type.options.size(); ++k) options[k] = type.options[k].default_value;
  return options;
}

std::string describe_options(const DeformerType& type, const StageOptions& options) {
  std::ostringstream text;
  for (std::size_t k = 0; k < type.options.size(); ++k) {
    const DeformerOption& option = type.options[k];
    text << (k == 0 ? "" : ", ") << option.key << " ";
    if (option.choices.empty()) {
      text << options[k];
    } else {
      text << option.choices[static_cast<std::size_t>(options[k])];
    }
  }
  return text.str();
}

}  // namespace finflex

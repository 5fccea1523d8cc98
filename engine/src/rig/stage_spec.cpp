// Building rig stages in code (finflex/rig.hpp): make_stage and set_option, checked
// against the deformer registry as a rig file's stages are.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "finflex/error.hpp"
#include "finflex/rig.hpp"

namespace finflex {
namespace {

std::size_t option_index(const StageSpec& stage, const std::string& key) {
  if (stage.deformer == nullptr) {
    throw Error(ErrorCode::kInvalidArgument, "deformer",
                "the stage has no deformer: make it with make_stage()");
  }
  const std::vector<DeformerOption>& options = stage.deformer->options;
  const auto found = std::find_if(options.begin(), options.end(),
                                  [&](const DeformerOption& o) { return key == o.key; });
  if (found == options.end()) {
    std::string keys;
    for (const DeformerOption& o : options) keys += (keys.empty() ? "" : ", ") + std::string(o.key);
    throw Error(ErrorCode::kInvalidArgument, key,
                "'" + key + "' is not an option of the " + stage.deformer->name +
                    " (its options: " + (keys.empty() ? "none" : keys) + ")");
  }
  return static_cast<std::size_t>(found - options.begin());
}

}  // namespace

StageSpec make_stage(const std::string& deformer, const std::string& param) {
  const DeformerType* type = find_deformer_type(deformer);
  if (type == nullptr) {
    throw Error(
        ErrorCode::kInvalidArgument, "deformer",
        "deformer '" + deformer + "' is not registered (expected " + deformer_type_names() + ")");
  }
  StageSpec stage;
  stage.deformer = type;
  stage.options = default_options(*type);
  stage.param = param;
  return stage;
}

void set_option(StageSpec& stage, const std::string& key, double value) {
  const std::size_t k = option_index(stage, key);
  const DeformerOption& option = stage.deformer->options[k];
  if (!option.choices.empty() || !std::isfinite(value) || value < option.minimum ||
      value > option.maximum || (option.integer && value != std::floor(value))) {
    std::ostringstream message;
    message.precision(9);
    message << key << " = " << value << " is not a valid " << stage.deformer->name << " " << key
            << " (" << option.meaning << ")";
    throw Error(ErrorCode::kInvalidArgument, key, message.str());
  }
  stage.options[k] = value;
}

void set_option(StageSpec& stage, const std::string& key, const std::string& choice) {
  const std::size_t k = option_index(stage, key);
  const DeformerOption& option = stage.deformer->options[k];
  for (std::size_t c = 0; c < option.choices.size(); ++c) {
    if (choice == option.choices[c]) {
      stage.options[k] = static_cast<double>(c);
      return;
    }
  }
  throw Error(ErrorCode::kInvalidArgument, key,
              key + " '" + choice + "' is not a choice of the " + stage.deformer->name + " (" +
                  option.meaning + ")");
}

}  // namespace finflex

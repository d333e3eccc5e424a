#include "vec/normalize_config.hpp"

#include <charconv>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "base/number_text.hpp"
#include "base/option_table.hpp"
#include "vec/normalization_state.hpp"

namespace upkie_rl {

namespace key = normalization_state;

void NormalizeConfig::declare_options(OptionTable& table, const std::string& prefix) {
  const auto name = [&prefix](const char* setting) { return prefix + setting; };
  constexpr bool kMinExcluded = true;
  table.add_boolean(name(key::kObservations), &observations, "normalise observations");
  table.add_boolean(name(key::kRewards), &rewards, "normalise rewards by the return's std");
  table.add_real(name(key::kClipObservations), &clip_observations, 0, kMaxNormalizationClip,
                 "clip normalised observations to +-it", kMinExcluded);
  table.add_real(name(key::kClipRewards), &clip_rewards, 0, kMaxNormalizationClip,
                 "clip normalised rewards to +-it", kMinExcluded);
  table.add_real(name(key::kGamma), &gamma, 0, 1, "discount of the return", kMinExcluded);
  table.add_real(name(key::kEpsilon), &epsilon, 0, 1, "added to variances", kMinExcluded);
}

void check_normalize_config(const NormalizeConfig& config) {
  // The table binds mutable fields: a copy, read only.
  NormalizeConfig copy = config;
  OptionTable table;
  copy.declare_options(table, "");
  table.check([](const std::string& name) { return "normalization " + name; }, "normalization");
}

nlohmann::json normalize_config_to_json(const NormalizeConfig& config) {
  NormalizeConfig copy = config;
  OptionTable table;
  copy.declare_options(table, "");
  nlohmann::json json = nlohmann::json::object();
  for (const OptionInfo& option : table.info()) {
    // The table writes the shortest text that reads back exactly (base/number_text.hpp).
    const std::string text = table.value_text(option.name);
    if (option.type == OptionInfo::Type::kBoolean) {
      json[option.name] = text == "true";
    } else {
      double value = 0.0;
      std::from_chars(text.data(), text.data() + text.size(), value);
      json[option.name] = value;
    }
  }
  return json;
}

NormalizeConfig normalize_config_from_json(const nlohmann::json& json) {
  if (!json.is_object()) {
    throw std::invalid_argument(std::string(key::kConfig) + " must be an object");
  }
  NormalizeConfig config;
  OptionTable table;
  config.declare_options(table, "");
  for (const OptionInfo& option : table.info()) {
    const std::string where = std::string(key::kConfig) + "." + option.name;
    const bool boolean = option.type == OptionInfo::Type::kBoolean;
    const auto found = json.find(option.name);
    if (found == json.end() || (boolean ? !found->is_boolean() : !found->is_number())) {
      throw std::invalid_argument(where + (boolean ? " must be a boolean" : " must be a number"));
    }
    // As text, which the table reads back exactly.
    table.read(option.name,
               boolean ? std::string(found->get<bool>() ? "true" : "false")
                       : shortest_text(found->get<double>()),
               where);
  }
  check_normalize_config(config);
  return config;
}

}  // namespace upkie_rl

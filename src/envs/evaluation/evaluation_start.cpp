#include "envs/evaluation/evaluation_start.hpp"

#include <algorithm>
#include <sstream>

#include "envs/registry/registry.hpp"

namespace upkie_rl {

EnvOptions evaluation_start_options(const std::string& env_id, const EnvOptions& given) {
  const std::vector<OptionInfo> accepted = env_option_info(env_id);
  EnvOptions added;
  for (const EvaluationStartBound& bound : kEvaluationStart) {
    const auto info = std::find_if(accepted.begin(), accepted.end(),
                                   [&](const OptionInfo& o) { return o.name == bound.option; });
    if (info == accepted.end() || std::stod(info->default_value) != 0.0) continue;
    const bool is_given = std::any_of(given.begin(), given.end(), [&](const auto& option) {
      return option.first == bound.option;
    });
    if (is_given) continue;
    std::ostringstream value;
    value << bound.value;
    added.emplace_back(bound.option, value.str());
  }
  return added;
}

EnvOptions with_evaluation_start(const std::string& env_id, const EnvOptions& given) {
  EnvOptions options = given;
  const EnvOptions added = evaluation_start_options(env_id, given);
  options.insert(options.end(), added.begin(), added.end());
  return options;
}

namespace {

/// The value of `option` in `options` (the last one given wins), else its default for
/// `env_id`, else 0 (an id without that option).
double start_bound(const std::string& env_id, const EnvOptions& options, const char* option) {
  for (auto it = options.rbegin(); it != options.rend(); ++it) {
    if (it->first == option) return std::stod(it->second);
  }
  const std::vector<OptionInfo> accepted = env_option_info(env_id);
  const auto info = std::find_if(accepted.begin(), accepted.end(),
                                 [&](const OptionInfo& o) { return o.name == option; });
  return info == accepted.end() ? 0.0 : std::stod(info->default_value);
}

}  // namespace

std::string evaluation_start_words(const std::string& env_id, const EnvOptions& options,
                                   bool exact_start) {
  for (const EvaluationStartBound& bound : kEvaluationStart) {
    if (start_bound(env_id, options, bound.option) != 0.0) return "from random starts";
  }
  return exact_start ? "from the exact start (--exact-start)" : "from the environment's own start";
}

std::string identical_episodes_warning(std::span<const double> returns,
                                       std::span<const int> lengths) {
  if (returns.size() < 2 || lengths.size() != returns.size()) return {};
  for (std::size_t e = 1; e < returns.size(); ++e) {
    if (returns[e] != returns[0] || lengths[e] != lengths[0]) return {};
  }
  std::ostringstream text;
  text << "all " << returns.size() << " episodes were identical (return " << returns[0]
       << ", length " << lengths[0]
       << "): the environment starts every episode from the same state; give it an initial-state "
          "randomisation (init_rand_pitch=...) or leave out the exact start";
  return text.str();
}

}  // namespace upkie_rl

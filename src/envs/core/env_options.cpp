#include "envs/core/env_options.hpp"

#include <stdexcept>

namespace upkie_rl {

EnvOptions parse_env_options(const std::vector<std::string>& key_values) {
  EnvOptions options;
  options.reserve(key_values.size());
  for (const std::string& key_value : key_values) {
    const std::size_t equal = key_value.find('=');
    if (equal == std::string::npos || equal == 0 || equal + 1 == key_value.size()) {
      throw std::invalid_argument("malformed environment option \"" + key_value +
                                  "\": expected key=value");
    }
    options.emplace_back(key_value.substr(0, equal), key_value.substr(equal + 1));
  }
  return options;
}

std::string format_env_options(const EnvOptions& options) {
  std::string text;
  for (const auto& [key, value] : options) text += (text.empty() ? "" : " ") + key + "=" + value;
  return text;
}

}  // namespace upkie_rl

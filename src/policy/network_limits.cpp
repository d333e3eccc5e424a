#include "policy/network_limits.hpp"

#include <stdexcept>

#include "base/setting_bounds.hpp"
#include "policy/parameter_layout.hpp"

namespace upkie_rl {

void check_hidden_sizes(const std::string& name, const std::vector<std::int64_t>& sizes) {
  if (sizes.empty()) throw std::invalid_argument(name + ": must not be empty");
  check_setting(name + " (number of layers)", static_cast<std::int64_t>(sizes.size()), 1,
                kMaxHiddenLayers);
  for (std::int64_t size : sizes) check_setting(name, size, 1, kMaxLayerWidth);
}

std::int64_t check_network_size(std::int64_t observation_size, std::int64_t action_size,
                                const std::vector<std::int64_t>& actor_hidden,
                                const std::vector<std::int64_t>& critic_hidden,
                                const std::string& actor_name, const std::string& critic_name) {
  check_setting("observation size", observation_size, 1, kMaxLayerWidth);
  check_setting("action size", action_size, 1, kMaxLayerWidth);
  check_hidden_sizes(actor_name, actor_hidden);
  check_hidden_sizes(critic_name, critic_hidden);
  // Widths <= 2^16 and at most 33 layers per network: the count fits an int64.
  const std::int64_t count =
      actor_critic_layout(observation_size, action_size, actor_hidden, critic_hidden).size;
  if (count > kMaxParameters) {
    throw std::invalid_argument(actor_name + " and " + critic_name + ": " + std::to_string(count) +
                                " parameters exceed the limit " + std::to_string(kMaxParameters));
  }
  return count;
}

}  // namespace upkie_rl

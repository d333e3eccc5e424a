#include "rl/ppo/rollout_buffer.hpp"

#include <stdexcept>
#include <string>

#include "rl/ppo/tensor_span.hpp"

namespace upkie_rl {

void compute_gae(std::span<const float> rewards, std::span<const float> values,
                 std::span<const float> dones, std::span<const float> last_values,
                 std::int64_t num_steps, std::int64_t num_envs, double gamma, double lambda,
                 std::span<float> advantages, std::span<float> returns) {
  const auto n = static_cast<std::size_t>(num_steps * num_envs);
  if (rewards.size() != n || values.size() != n || dones.size() != n || advantages.size() != n ||
      returns.size() != n || last_values.size() != static_cast<std::size_t>(num_envs)) {
    throw std::invalid_argument("compute_gae: buffers must hold " + std::to_string(n) +
                                " transitions and " + std::to_string(num_envs) + " last values");
  }
  for (std::int64_t env = 0; env < num_envs; ++env) {
    double next_value = last_values[env];
    double next_advantage = 0.0;
    for (std::int64_t t = num_steps - 1; t >= 0; --t) {
      const std::size_t i = static_cast<std::size_t>(t * num_envs + env);
      const double not_done = 1.0 - dones[i];
      const double delta = rewards[i] + gamma * next_value * not_done - values[i];
      next_advantage = delta + gamma * lambda * not_done * next_advantage;
      advantages[i] = static_cast<float>(next_advantage);
      returns[i] = static_cast<float>(next_advantage + values[i]);
      next_value = values[i];
    }
  }
}

RolloutBuffer::RolloutBuffer(std::int64_t num_steps, std::int64_t num_envs,
                             std::int64_t observation_size, std::int64_t action_size)
    : num_steps_(num_steps), num_envs_(num_envs) {
  if (num_steps < 1 || num_envs < 1) {
    throw std::invalid_argument("RolloutBuffer: needs at least one step and one env");
  }
  observations_ = torch::zeros({num_steps, num_envs, observation_size});
  actions_ = torch::zeros({num_steps, num_envs, action_size});
  rewards_ = torch::zeros({num_steps, num_envs});
  dones_ = torch::zeros({num_steps, num_envs});
  values_ = torch::zeros({num_steps, num_envs});
  log_probs_ = torch::zeros({num_steps, num_envs});
  advantages_ = torch::zeros({num_steps, num_envs});
  returns_ = torch::zeros({num_steps, num_envs});
}

void RolloutBuffer::compute_returns_and_advantages(std::span<const float> last_values, double gamma,
                                                   double lambda) {
  compute_gae(tensor_values(rewards_), tensor_values(values_), tensor_values(dones_), last_values,
              num_steps_, num_envs_, gamma, lambda, tensor_values(advantages_),
              tensor_values(returns_));
}

}  // namespace upkie_rl

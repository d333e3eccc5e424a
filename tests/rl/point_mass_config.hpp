#pragma once
/// @file
/// The training configuration of the PPO tests on the point mass (point_mass_vector_env.hpp):
/// small networks and rollouts that learn it in a few tens of thousands of steps.

#include <cstdint>

#include "rl/runs/training_config.hpp"

namespace upkie_rl::testing {

inline TrainingConfig point_mass_config(std::int64_t num_envs = 4) {
  TrainingConfig config;
  config.env_id = "point-mass";
  config.num_envs = num_envs;
  config.policy.actor_hidden_sizes = {32, 32};
  config.policy.critic_hidden_sizes = {32, 32};
  config.ppo.total_timesteps = 40'000;
  config.ppo.n_steps = 512;
  config.ppo.batch_size = 64;
  config.ppo.n_epochs = 5;
  config.ppo.learning_rate_initial = 1e-3;
  config.ppo.learning_rate_final = 3e-4;
  config.seed = 3;
  return config;
}

}  // namespace upkie_rl::testing

#pragma once
/// @file
/// How the actor-critic's parameters are laid out in its one flat float32 buffer (the
/// "policy.parameters" tensor of a checkpoint), shared by the trainer's ActorCritic and the
/// torch-free DeployedPolicy:
///
///   actor layer 0 weight (out x in, row-major), actor layer 0 bias (out), ..., actor output
///   layer (action_size x last hidden) and bias, then the critic's layers the same way
///   (output size 1), then log σ (action_size).

#include <cstdint>
#include <vector>

namespace upkie_rl {

/// Number of parameters of an MLP with these layer sizes (weights and biases).
inline std::int64_t mlp_parameter_count(std::int64_t input_size,
                                        const std::vector<std::int64_t>& hidden_sizes,
                                        std::int64_t output_size) {
  std::int64_t count = 0;
  std::int64_t in = input_size;
  for (std::int64_t out : hidden_sizes) {
    count += out * in + out;
    in = out;
  }
  return count + output_size * in + output_size;
}

/// Number of parameters of the actor, the critic and log σ together.
inline std::int64_t actor_critic_parameter_count(std::int64_t observation_size,
                                                 std::int64_t action_size,
                                                 const std::vector<std::int64_t>& actor_hidden,
                                                 const std::vector<std::int64_t>& critic_hidden) {
  return mlp_parameter_count(observation_size, actor_hidden, action_size) +
         mlp_parameter_count(observation_size, critic_hidden, 1) + action_size;
}

}  // namespace upkie_rl

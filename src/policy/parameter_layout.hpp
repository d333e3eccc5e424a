#pragma once
/// @file
/// How the actor-critic's parameters are laid out in its one flat float32 buffer (the
/// "policy.parameters" tensor of a checkpoint), shared by the trainer's ActorCritic and the
/// torch-free DeployedPolicy:
///
///   actor layer 0 weight (out x in, row-major), actor layer 0 bias (out), ..., actor output
///   layer (action_size x last hidden) and bias, then the critic's layers the same way
///   (output size 1), then log σ (action_size).
///
/// Every layer is y = x·Wᵀ + b, followed by the activation except for the output layer.

#include <cstdint>
#include <vector>

namespace upkie_rl {

/// Where one dense layer's parameters lie in the flat buffer.
struct DenseLayerLayout {
  std::int64_t in = 0;      ///< Input size.
  std::int64_t out = 0;     ///< Output size.
  std::int64_t weight = 0;  ///< Offset of the out x in weights, row-major.
  std::int64_t bias = 0;    ///< Offset of the out biases, right after the weights.
};

/// The layers of an MLP (hidden layers, then the output layer) whose parameters start at
/// `offset`; advances `offset` past them.
inline std::vector<DenseLayerLayout> mlp_layout(std::int64_t input_size,
                                                const std::vector<std::int64_t>& hidden_sizes,
                                                std::int64_t output_size, std::int64_t& offset) {
  std::vector<DenseLayerLayout> layers;
  std::vector<std::int64_t> sizes = hidden_sizes;
  sizes.push_back(output_size);
  std::int64_t in = input_size;
  for (std::int64_t out : sizes) {
    layers.push_back({in, out, offset, offset + out * in});
    offset += out * in + out;
    in = out;
  }
  return layers;
}

/// The whole buffer: actor, critic, log σ.
struct ActorCriticLayout {
  std::vector<DenseLayerLayout> actor;   ///< Output size action_size.
  std::vector<DenseLayerLayout> critic;  ///< Output size 1.
  std::int64_t log_std = 0;              ///< Offset of the action_size log σ.
  std::int64_t size = 0;                 ///< Number of parameters.
};

inline ActorCriticLayout actor_critic_layout(std::int64_t observation_size,
                                             std::int64_t action_size,
                                             const std::vector<std::int64_t>& actor_hidden,
                                             const std::vector<std::int64_t>& critic_hidden) {
  ActorCriticLayout layout;
  std::int64_t offset = 0;
  layout.actor = mlp_layout(observation_size, actor_hidden, action_size, offset);
  layout.critic = mlp_layout(observation_size, critic_hidden, 1, offset);
  layout.log_std = offset;
  layout.size = offset + action_size;
  return layout;
}

}  // namespace upkie_rl

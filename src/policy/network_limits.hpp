#pragma once
/// @file
/// The largest actor-critic the toolkit builds or loads, checked before anything is
/// allocated: by the training configuration (rl/runs/training_config.hpp) and by the checkpoint
/// gate (policy/checkpoint_gate.hpp), so that a setting or a header cannot ask libtorch or
/// the deployed policy for gigabytes.

#include <cstdint>
#include <string>
#include <vector>

namespace upkie_rl {

/// Widest layer, and widest observation or action vector.
inline constexpr std::int64_t kMaxLayerWidth = 65'536;
/// Most hidden layers per network.
inline constexpr std::int64_t kMaxHiddenLayers = 32;
/// Most parameters of the actor and critic together (256 MB of float32; the trainer keeps
/// about five copies: weights, gradients, two Adam moments, the minibatch's).
inline constexpr std::int64_t kMaxParameters = std::int64_t{1} << 26;

/// Throws std::invalid_argument naming `name` when `sizes` is empty, longer than
/// kMaxHiddenLayers or has a width outside [1, kMaxLayerWidth].
void check_hidden_sizes(const std::string& name, const std::vector<std::int64_t>& sizes);

/// Checks the sizes (check_hidden_sizes, observation and action sizes in
/// [1, kMaxLayerWidth]) and the parameter count (at most kMaxParameters); returns the count.
/// Throws std::invalid_argument naming the culprit; `actor_name` and `critic_name` name the
/// hidden sizes' settings.
std::int64_t check_network_size(std::int64_t observation_size, std::int64_t action_size,
                                const std::vector<std::int64_t>& actor_hidden,
                                const std::vector<std::int64_t>& critic_hidden,
                                const std::string& actor_name = "policy.actor_hidden_sizes",
                                const std::string& critic_name = "policy.critic_hidden_sizes");

}  // namespace upkie_rl

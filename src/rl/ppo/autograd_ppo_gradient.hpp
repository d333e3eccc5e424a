#pragma once
/// @file
/// The gradient of the PPO loss by libtorch's autograd, for the policies the hand-written
/// PpoGradient does not cover (every activation but relu and tanh), and as its reference in
/// tests and benchmarks.

#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/ppo_gradient.hpp"
#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// Evaluates `policy` on `batch` and overwrites policy.flat_gradients() with the gradient
/// of compute_ppo_loss(policy.evaluate_actions(...), batch, config).total by autograd;
/// returns the loss terms. The same contract as PpoGradient::compute for any activation,
/// at the price of a graph and allocations per call (docs/training.md has the figures).
/// Throws std::invalid_argument when the batch is empty or its spans are not rows of the
/// policy's sizes.
PpoLossStatistics autograd_ppo_gradient(const PpoMinibatchView& batch, ActorCritic& policy,
                                        const PpoConfig& config);

}  // namespace upkie_rl

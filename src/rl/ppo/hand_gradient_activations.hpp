#pragma once
/// @file
/// Which activations the hand-written PPO gradient (rl/ppo/ppo_gradient.hpp) differentiates,
/// apart from that class: the training configuration checks `ppo.gradient` with it, and
/// the configuration's parser stays free of libtorch's headers (PpoGradient works on an
/// ActorCritic), so that it compiles with clang for its fuzz target.

#include "policy/activation.hpp"

namespace upkie_rl {

/// Whether the hand-written backward pass knows this activation's derivative: relu and
/// tanh (the others train through rl/ppo/autograd_ppo_gradient.hpp).
constexpr bool hand_gradient_covers(Activation activation) {
  return activation == Activation::kReLU || activation == Activation::kTanh;
}

}  // namespace upkie_rl

#pragma once
/// @file
/// policy/activation.hpp's activations applied to torch tensors, for the trainer's two
/// forward passes (ActorCritic's differentiable one and PolicyInference's in-place one).

#include <torch/torch.h>

#include "policy/activation.hpp"

namespace upkie_rl {

/// f(x), differentiable.
torch::Tensor activate(Activation activation, const torch::Tensor& x);
/// x ← f(x) in place, allocating nothing (for PolicyInference's rollout hot path).
void activate_in_place(Activation activation, torch::Tensor& x);

}  // namespace upkie_rl

#pragma once
/// @file
/// The PPO loss on one minibatch (SB3 semantics): clipped surrogate, clipped value loss,
/// entropy bonus, and the approximate KL and clip fraction that are logged.

#include <torch/torch.h>

#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/ppo_minibatch.hpp"
#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// The loss and its terms. `total` is differentiable; the others are detached.
struct PpoLoss {
  torch::Tensor total;                 ///< L_pg + c_ent·L_ent + c_v·L_v.
  torch::Tensor policy_gradient_loss;  ///< −mean(min(A·ρ, A·clamp(ρ, 1 ± ε))).
  torch::Tensor value_loss;            ///< mean((R − V_pred)²), V_pred clipped around V_old.
  torch::Tensor entropy_loss;          ///< −mean(entropy).
  torch::Tensor approx_kl;             ///< mean((ρ − 1) − log ρ).
  torch::Tensor clip_fraction;         ///< mean(|ρ − 1| > ε).
};

/// Computes the loss from the current policy's `evaluation` of `batch`. Advantages are
/// normalised over the minibatch, (A − mean)/(std + 1e-8) with an unbiased std, when
/// config.normalize_advantage and the minibatch has more than one sample.
PpoLoss compute_ppo_loss(const ActionEvaluation& evaluation, const PpoMinibatch& batch,
                         const PpoConfig& config);

/// 1 − Var(returns − values)/Var(returns) (population variances); NaN when Var(returns) = 0.
double explained_variance(const torch::Tensor& values, const torch::Tensor& returns);

}  // namespace upkie_rl

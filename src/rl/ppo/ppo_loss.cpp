#include "rl/ppo/ppo_loss.hpp"

#include <limits>

namespace upkie_rl {

PpoLoss compute_ppo_loss(const ActionEvaluation& evaluation, const PpoMinibatch& batch,
                         const PpoConfig& config) {
  torch::Tensor advantages = batch.advantages;
  if (config.normalize_advantage && advantages.numel() > 1) {
    advantages = (advantages - advantages.mean()) / (advantages.std() + 1e-8);
  }
  const torch::Tensor log_ratio = evaluation.log_prob - batch.old_log_prob;
  const torch::Tensor ratio = torch::exp(log_ratio);
  const torch::Tensor surrogate = advantages * ratio;
  const torch::Tensor clipped_surrogate =
      advantages * torch::clamp(ratio, 1.0 - config.clip_range, 1.0 + config.clip_range);
  PpoLoss loss;
  const torch::Tensor policy_gradient_loss = -torch::min(surrogate, clipped_surrogate).mean();

  torch::Tensor predicted_values = evaluation.values;
  if (config.clip_range_vf > 0.0) {
    predicted_values = batch.old_values + torch::clamp(evaluation.values - batch.old_values,
                                                       -config.clip_range_vf, config.clip_range_vf);
  }
  const torch::Tensor value_loss = (batch.returns - predicted_values).square().mean();
  // The Gaussian's entropy does not depend on the state: its mean is the entropy itself.
  const torch::Tensor entropy_loss = -evaluation.entropy;

  loss.total = policy_gradient_loss + config.vf_coef * value_loss;
  // With the seed's ent_coef = 0 the term is left out of the graph (same value, fewer ops).
  if (config.ent_coef != 0.0) loss.total = loss.total + config.ent_coef * entropy_loss;
  loss.policy_gradient_loss = policy_gradient_loss.detach();
  loss.value_loss = value_loss.detach();
  loss.entropy_loss = entropy_loss.detach();
  {
    torch::NoGradGuard no_grad;
    loss.approx_kl = ((ratio - 1.0) - log_ratio).mean();
    loss.clip_fraction = ((ratio - 1.0).abs() > config.clip_range).to(torch::kFloat32).mean();
  }
  return loss;
}

double explained_variance(const torch::Tensor& values, const torch::Tensor& returns) {
  torch::NoGradGuard no_grad;
  const double variance = returns.var(/*unbiased=*/false).item<double>();
  if (variance == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return 1.0 - (returns - values).var(/*unbiased=*/false).item<double>() / variance;
}

}  // namespace upkie_rl

#pragma once
/// @file
/// The on-policy rollout buffer of PPO and generalised advantage estimation (GAE).

#include <torch/torch.h>

#include <cstdint>
#include <span>

#include "rl/ppo/ppo_minibatch.hpp"

namespace upkie_rl {

/// Computes GAE advantages and value targets over a rollout of `num_steps` x `num_envs`
/// (step-major) transitions:
///   δ_t = r_t + γ·V_{t+1}·(1 − done_t) − V_t,  A_t = δ_t + γλ(1 − done_t)·A_{t+1},
///   returns = A + V,
/// where V_{t+1} is `last_values` after the last step and done_t = 1 when the episode ended
/// at step t (truncated episodes' rewards already carry γ·V(final observation)).
void compute_gae(std::span<const float> rewards, std::span<const float> values,
                 std::span<const float> dones, std::span<const float> last_values,
                 std::int64_t num_steps, std::int64_t num_envs, double gamma, double lambda,
                 std::span<float> advantages, std::span<float> returns);

/// Fixed-size storage for one rollout, filled one vector step at a time.
class RolloutBuffer {
 public:
  RolloutBuffer(std::int64_t num_steps, std::int64_t num_envs, std::int64_t observation_size,
                std::int64_t action_size);

  std::int64_t num_steps() const { return num_steps_; }
  std::int64_t num_envs() const { return num_envs_; }
  std::int64_t size() const { return num_steps_ * num_envs_; }

  /// Row pointers of step `t` (num_envs entries each), for the rollout to write into.
  float* observations(std::int64_t t) { return row(observations_, t); }
  float* actions(std::int64_t t) { return row(actions_, t); }
  float* rewards(std::int64_t t) { return row(rewards_, t); }
  float* dones(std::int64_t t) { return row(dones_, t); }
  float* values(std::int64_t t) { return row(values_, t); }
  float* log_probs(std::int64_t t) { return row(log_probs_, t); }

  /// Runs compute_gae over the whole buffer.
  void compute_returns_and_advantages(std::span<const float> last_values, double gamma,
                                      double lambda);

  /// Flat views (size() rows) for the update.
  torch::Tensor flat_observations() const { return observations_.view({size(), -1}); }
  torch::Tensor flat_actions() const { return actions_.view({size(), -1}); }
  torch::Tensor flat_values() const { return values_.view({-1}); }
  torch::Tensor flat_log_probs() const { return log_probs_.view({-1}); }
  torch::Tensor flat_advantages() const { return advantages_.view({-1}); }
  torch::Tensor flat_returns() const { return returns_.view({-1}); }
  /// The six flat views as one minibatch of the whole rollout, in collection order.
  PpoMinibatch flat() const {
    return {flat_observations(), flat_actions(),    flat_log_probs(),
            flat_values(),       flat_advantages(), flat_returns()};
  }

 private:
  float* row(torch::Tensor& tensor, std::int64_t t) {
    return tensor.data_ptr<float>() + t * (tensor.numel() / num_steps_);
  }

  std::int64_t num_steps_;
  std::int64_t num_envs_;
  torch::Tensor observations_;  // num_steps x num_envs x observation_size
  torch::Tensor actions_;       // num_steps x num_envs x action_size (unclipped samples)
  torch::Tensor rewards_;       // num_steps x num_envs
  torch::Tensor dones_;
  torch::Tensor values_;
  torch::Tensor log_probs_;
  torch::Tensor advantages_;
  torch::Tensor returns_;
};

}  // namespace upkie_rl

#pragma once
/// @file
/// Adam (torch.optim.Adam semantics, no weight decay, no amsgrad) over one flat parameter
/// tensor, and global-norm gradient clipping. Working on the flat buffer makes a step a
/// handful of tensor operations whatever the number of layers.

#include <torch/torch.h>

#include <cstdint>

namespace upkie_rl {

/// Adam's hyperparameters. PPO uses eps = 1e-5, not the library default 1e-8.
struct AdamConfig {
  double learning_rate = 3e-4;
  double beta1 = 0.9;
  double beta2 = 0.999;
  double eps = 1e-5;
};

/// Adam over a flat float tensor of parameters and its flat gradient.
class FlatAdam {
 public:
  /// Keeps shallow handles to `parameters` and `gradients` (same shape), updated in place.
  FlatAdam(torch::Tensor parameters, torch::Tensor gradients, const AdamConfig& config);

  /// One Adam step with the current gradients.
  void step();

  void set_learning_rate(double learning_rate) { config_.learning_rate = learning_rate; }
  double learning_rate() const { return config_.learning_rate; }
  const AdamConfig& config() const { return config_; }

  /// Number of steps taken (Adam's bias correction counter).
  std::int64_t step_count() const { return step_count_; }
  /// First and second moment estimates, for checkpoints.
  const torch::Tensor& exp_avg() const { return exp_avg_; }
  const torch::Tensor& exp_avg_sq() const { return exp_avg_sq_; }

  /// Restores the moments and step count; throws std::invalid_argument on a size mismatch.
  void load_state(const torch::Tensor& exp_avg, const torch::Tensor& exp_avg_sq,
                  std::int64_t step_count);

 private:
  torch::Tensor parameters_;
  torch::Tensor gradients_;
  AdamConfig config_;
  torch::Tensor exp_avg_;
  torch::Tensor exp_avg_sq_;
  torch::Tensor denominator_;  // scratch
  std::int64_t step_count_ = 0;
};

/// Scales `gradients` in place so that their L2 norm is at most `max_norm`
/// (torch.nn.utils.clip_grad_norm_ semantics, coefficient max_norm / (norm + 1e-6)).
/// Returns the norm before clipping.
double clip_gradient_norm(torch::Tensor& gradients, double max_norm);

}  // namespace upkie_rl

#include "rl/ppo/flat_adam.hpp"

#include <cmath>
#include <stdexcept>

namespace upkie_rl {

FlatAdam::FlatAdam(torch::Tensor parameters, torch::Tensor gradients, const AdamConfig& config)
    : parameters_(std::move(parameters)), gradients_(std::move(gradients)), config_(config) {
  if (!parameters_.sizes().equals(gradients_.sizes())) {
    throw std::invalid_argument("FlatAdam: parameters and gradients differ in shape");
  }
  exp_avg_ = torch::zeros_like(parameters_);
  exp_avg_sq_ = torch::zeros_like(parameters_);
  denominator_ = torch::zeros_like(parameters_);
}

void FlatAdam::step() {
  torch::NoGradGuard no_grad;
  ++step_count_;
  const double t = static_cast<double>(step_count_);
  exp_avg_.mul_(config_.beta1).add_(gradients_, 1.0 - config_.beta1);
  exp_avg_sq_.mul_(config_.beta2).addcmul_(gradients_, gradients_, 1.0 - config_.beta2);
  const double bias_correction1 = 1.0 - std::pow(config_.beta1, t);
  const double bias_correction2_sqrt = std::sqrt(1.0 - std::pow(config_.beta2, t));
  const double step_size = config_.learning_rate / bias_correction1;
  at::sqrt_out(denominator_, exp_avg_sq_);
  denominator_.div_(bias_correction2_sqrt).add_(config_.eps);
  parameters_.addcdiv_(exp_avg_, denominator_, -step_size);
}

void FlatAdam::load_state(const torch::Tensor& exp_avg, const torch::Tensor& exp_avg_sq,
                          std::int64_t step_count) {
  if (exp_avg.numel() != exp_avg_.numel() || exp_avg_sq.numel() != exp_avg_sq_.numel()) {
    throw std::invalid_argument("optimiser state has " + std::to_string(exp_avg.numel()) +
                                " values, the policy " + std::to_string(exp_avg_.numel()));
  }
  if (step_count < 0) throw std::invalid_argument("optimiser state: negative step count");
  torch::NoGradGuard no_grad;
  exp_avg_.copy_(exp_avg.view_as(exp_avg_));
  exp_avg_sq_.copy_(exp_avg_sq.view_as(exp_avg_sq_));
  step_count_ = step_count;
}

double clip_gradient_norm(torch::Tensor& gradients, double max_norm) {
  torch::NoGradGuard no_grad;
  const double norm = gradients.norm().item<double>();
  const double coefficient = max_norm / (norm + 1e-6);
  if (coefficient < 1.0) gradients.mul_(coefficient);
  return norm;
}

}  // namespace upkie_rl

#include "rl/ppo/flat_adam.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "policy/checkpoint_gate.hpp"

namespace upkie_rl {
namespace {

TEST(FlatAdam, MatchesTorchAdamStepByStep) {
  torch::manual_seed(3);
  const torch::Tensor initial = torch::randn({10});
  torch::Tensor reference = initial.clone().requires_grad_(true);
  torch::optim::Adam torch_adam({reference},
                                torch::optim::AdamOptions(1e-2).betas({0.9, 0.999}).eps(1e-5));
  torch::Tensor parameters = initial.clone();
  torch::Tensor gradients = torch::zeros({10});
  FlatAdam adam(parameters, gradients, AdamConfig{1e-2, 0.9, 0.999, 1e-5});
  for (int step = 0; step < 5; ++step) {
    const torch::Tensor gradient = torch::randn({10});
    reference.mutable_grad() = gradient.clone();
    torch_adam.step();
    gradients.copy_(gradient);
    adam.step();
    ASSERT_TRUE(torch::allclose(parameters, reference.detach(), 1e-6, 1e-7)) << "step " << step;
  }
  EXPECT_EQ(adam.step_count(), 5);
}

TEST(FlatAdam, LearningRateChangesTheStep) {
  torch::Tensor parameters = torch::zeros({1});
  torch::Tensor gradients = torch::ones({1});
  FlatAdam adam(parameters, gradients, AdamConfig{1.0, 0.9, 0.999, 1e-5});
  adam.set_learning_rate(0.5);
  adam.step();
  // First step: m̂ = g, v̂ = g², so Δ = −lr·g/(|g| + eps) ≈ −0.5.
  EXPECT_NEAR(parameters.item<float>(), -0.5 / (1.0 + 1e-5), 1e-6);
}

TEST(FlatAdam, LoadStateChecksSizes) {
  torch::Tensor parameters = torch::zeros({4});
  torch::Tensor gradients = torch::zeros({4});
  FlatAdam adam(parameters, gradients, AdamConfig{});
  EXPECT_THROW(adam.load_state(torch::zeros({3}), torch::zeros({3}), 1), std::invalid_argument);
  adam.load_state(torch::ones({4}), torch::full({4}, 2.0f), 7);
  EXPECT_EQ(adam.step_count(), 7);
  EXPECT_FLOAT_EQ(adam.exp_avg_sq()[2].item<float>(), 2.0f);
}

// The checkpoint gate refuses moments with m² > kMaxAdamMomentRatio · v. Adam's own moments
// from any gradients stay within (1 − β1)² / ((1 − β2)(1 − β1² / β2)) · v (Cauchy–Schwarz on
// the two recurrences), so a checkpoint PPO writes always passes.
TEST(FlatAdam, MomentsStayWithinTheCheckpointGatesRatio) {
  const AdamConfig config;
  const double ratio_bound =
      (1.0 - config.beta1) * (1.0 - config.beta1) /
      ((1.0 - config.beta2) * (1.0 - config.beta1 * config.beta1 / config.beta2));
  EXPECT_NEAR(ratio_bound, 52.9, 0.1);
  EXPECT_LT(ratio_bound, kMaxAdamMomentRatio);
  // The gradients that come nearest the bound: g_i ∝ (β1² / β2)^(t − i) seen from step t,
  // so growing by β2 / β1² per step, for 40 steps; then ten random steps of mixed signs.
  torch::Tensor parameters = torch::zeros({3});
  torch::Tensor gradients = torch::zeros({3});
  FlatAdam adam(parameters, gradients, config);
  double largest_ratio = 0.0;
  double gradient = 1e-3;
  torch::manual_seed(5);
  for (int step = 0; step < 50; ++step) {
    gradient *= config.beta2 / (config.beta1 * config.beta1);
    gradients.copy_(step < 40 ? torch::full({3}, gradient) : torch::randn({3}));
    adam.step();
    const torch::Tensor ratio = adam.exp_avg().square() / adam.exp_avg_sq();
    largest_ratio = std::max(largest_ratio, ratio.max().item<double>());
  }
  EXPECT_GT(largest_ratio, 45.0);  // the sequence does approach the bound
  EXPECT_LE(largest_ratio, ratio_bound * (1.0 + 1e-5));
}

TEST(ClipGradientNorm, MatchesTorchClipGradNorm) {
  torch::manual_seed(4);
  const torch::Tensor gradient = torch::randn({20}) * 3.0;
  torch::Tensor parameter = torch::zeros({20}, torch::requires_grad());
  parameter.mutable_grad() = gradient.clone();
  const double torch_norm = torch::nn::utils::clip_grad_norm_({parameter}, 0.5);
  torch::Tensor flat = gradient.clone();
  const double norm = clip_gradient_norm(flat, 0.5);
  EXPECT_NEAR(norm, torch_norm, 1e-4);
  EXPECT_TRUE(torch::allclose(flat, parameter.grad(), 1e-5, 1e-7));
  EXPECT_NEAR(flat.norm().item<double>(), 0.5, 1e-5);
  // Below the threshold nothing changes.
  torch::Tensor small = torch::full({4}, 0.1f);
  clip_gradient_norm(small, 0.5);
  EXPECT_TRUE(torch::equal(small, torch::full({4}, 0.1f)));
}

}  // namespace
}  // namespace upkie_rl

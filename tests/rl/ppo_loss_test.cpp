#include "rl/ppo/ppo_loss.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace upkie_rl {
namespace {

// A fixed minibatch of three samples. New log-probabilities give ratios (1.5, 0.5, 1.1).
struct Fixture {
  PpoMinibatch batch;
  ActionEvaluation evaluation;
  PpoConfig config;
  Fixture() {
    batch.observations = torch::zeros({3, 1});
    batch.actions = torch::zeros({3, 1});
    batch.old_log_prob = torch::tensor({-1.0f, -2.0f, 0.5f});
    batch.old_values = torch::tensor({1.0f, 0.0f, 2.0f});
    batch.advantages = torch::tensor({1.0f, -1.0f, 0.5f});
    batch.returns = torch::tensor({3.0f, 0.0f, 2.05f});
    evaluation.log_prob =
        batch.old_log_prob + torch::tensor({std::log(1.5f), std::log(0.5f), std::log(1.1f)});
    evaluation.entropy = torch::tensor(1.3f);
    evaluation.values = torch::tensor({2.0f, -1.0f, 2.1f});
    config.clip_range = 0.2;
    config.clip_range_vf = 0.2;
    config.ent_coef = 0.01;
    config.vf_coef = 0.5;
  }
};

TEST(PpoLoss, EachTermMatchesHandComputedValues) {
  const Fixture f;
  const PpoLoss loss = compute_ppo_loss(f.evaluation, f.batch, f.config);

  // Advantages normalised by hand: mean 1/6, unbiased std sqrt(13/12).
  const double mean = 1.0 / 6.0;
  const double std =
      std::sqrt(((5.0 / 6) * (5.0 / 6) + (7.0 / 6) * (7.0 / 6) + (2.0 / 6) * (2.0 / 6)) / 2.0);
  const double a[3] = {(1 - mean) / (std + 1e-8), (-1 - mean) / (std + 1e-8),
                       (0.5 - mean) / (std + 1e-8)};
  const double ratio[3] = {1.5, 0.5, 1.1};
  const double clipped[3] = {1.2, 0.8, 1.1};
  double surrogate = 0.0;
  for (int i = 0; i < 3; ++i) surrogate += std::min(a[i] * ratio[i], a[i] * clipped[i]);
  const double policy_gradient_loss = -surrogate / 3.0;
  EXPECT_NEAR(loss.policy_gradient_loss.item<double>(), policy_gradient_loss, 1e-5);

  // Values clipped to old ± 0.2: (1.2, −0.2, 2.1); errors (1.8, 0.2, −0.05).
  const double value_loss = (1.8 * 1.8 + 0.2 * 0.2 + 0.05 * 0.05) / 3.0;
  EXPECT_NEAR(loss.value_loss.item<double>(), value_loss, 1e-5);

  EXPECT_NEAR(loss.entropy_loss.item<double>(), -1.3, 1e-6);
  EXPECT_NEAR(loss.total.item<double>(), policy_gradient_loss + 0.01 * -1.3 + 0.5 * value_loss,
              1e-5);

  const double approx_kl =
      ((0.5 - std::log(1.5)) + (-0.5 - std::log(0.5)) + (0.1 - std::log(1.1))) / 3.0;
  EXPECT_NEAR(loss.approx_kl.item<double>(), approx_kl, 1e-6);
  EXPECT_NEAR(loss.clip_fraction.item<double>(), 2.0 / 3.0, 1e-6);  // 1.5 and 0.5 clipped
}

TEST(PpoLoss, WithoutValueClippingOrNormalisation) {
  Fixture f;
  f.config.clip_range_vf = 0.0;
  f.config.normalize_advantage = false;
  const PpoLoss loss = compute_ppo_loss(f.evaluation, f.batch, f.config);
  // Unclipped values: errors (1, 1, −0.05).
  EXPECT_NEAR(loss.value_loss.item<double>(), (1.0 + 1.0 + 0.0025) / 3.0, 1e-6);
  // Raw advantages: min(1·1.5, 1·1.2) = 1.2; min(−0.5, −0.8) = −0.8; min(0.55, 0.55).
  EXPECT_NEAR(loss.policy_gradient_loss.item<double>(), -(1.2 - 0.8 + 0.55) / 3.0, 1e-6);
}

TEST(PpoLoss, ClippedSamplesGiveNoPolicyGradient) {
  Fixture f;
  f.config.normalize_advantage = false;
  torch::Tensor log_prob = f.evaluation.log_prob.clone().requires_grad_(true);
  f.evaluation.log_prob = log_prob;
  compute_ppo_loss(f.evaluation, f.batch, f.config).total.backward();
  // Sample 0 (A > 0, ratio 1.5 > 1.2) and 1 (A < 0, ratio 0.5 < 0.8) are clipped out;
  // sample 2 has gradient −A·ratio/3.
  EXPECT_FLOAT_EQ(log_prob.grad()[0].item<float>(), 0.0f);
  EXPECT_FLOAT_EQ(log_prob.grad()[1].item<float>(), 0.0f);
  EXPECT_NEAR(log_prob.grad()[2].item<float>(), -0.5 * 1.1 / 3.0, 1e-6);
}

TEST(ExplainedVariance, OneForPerfectPredictionsZeroForConstantOnes) {
  const torch::Tensor returns = torch::tensor({1.0f, 2.0f, 3.0f});
  EXPECT_NEAR(explained_variance(returns, returns), 1.0, 1e-9);
  EXPECT_NEAR(explained_variance(torch::full({3}, 2.0f), returns), 0.0, 1e-6);
  EXPECT_TRUE(std::isnan(explained_variance(returns, torch::ones({3}))));
}

}  // namespace
}  // namespace upkie_rl

#include "rl/ppo/actor_critic.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace upkie_rl {
namespace {

PolicyConfig small_config() {
  PolicyConfig config;
  config.actor_hidden_sizes = {16, 8};
  config.critic_hidden_sizes = {12};
  return config;
}

TEST(ActorCritic, CountsAndLaysOutParameters) {
  const ActorCritic policy(3, 2, small_config(), 0);
  // actor 3→16→8→2, critic 3→12→1, log σ 2.
  const std::int64_t expected =
      (16 * 3 + 16) + (8 * 16 + 8) + (2 * 8 + 2) + (12 * 3 + 12) + (1 * 12 + 1) + 2;
  EXPECT_EQ(policy.flat_parameters().numel(), expected);
  EXPECT_EQ(count_parameters(3, 2, small_config()), expected);
  EXPECT_EQ(policy.parameters().size(), 3u * 2 + 2u * 2 + 1u);
  // Each parameter is a view of the flat buffer where policy/parameter_layout.hpp puts it.
  const ActorCriticLayout layout = actor_critic_layout(3, 2, {16, 8}, {12});
  const float* flat = policy.flat_parameters().data_ptr<float>();
  auto expect_layers = [&](const std::vector<DenseLayer>& layers,
                           const std::vector<DenseLayerLayout>& expected) {
    ASSERT_EQ(layers.size(), expected.size());
    for (std::size_t i = 0; i < layers.size(); ++i) {
      EXPECT_EQ(layers[i].weight.data_ptr<float>(), flat + expected[i].weight);
      EXPECT_EQ(layers[i].bias.data_ptr<float>(), flat + expected[i].bias);
      EXPECT_EQ(layers[i].weight.sizes().vec(),
                (std::vector<std::int64_t>{expected[i].out, expected[i].in}));
    }
  };
  expect_layers(policy.actor_layers(), layout.actor);
  expect_layers(policy.critic_layers(), layout.critic);
  EXPECT_EQ(policy.log_std().data_ptr<float>(), flat + layout.log_std);
}

TEST(ActorCritic, OrthogonalInitialisationWithTheSb3Gains) {
  const ActorCritic policy(4, 1, PolicyConfig{}, 7);
  const auto& actor = policy.actor_layers();
  const auto& critic = policy.critic_layers();
  // 64x4 hidden weight: orthonormal columns times √2, so WᵀW = 2·I.
  EXPECT_TRUE(
      torch::allclose(actor[0].weight.t().mm(actor[0].weight), 2.0 * torch::eye(4), 1e-4, 1e-4));
  // 64x64: W·Wᵀ = 2·I.
  EXPECT_TRUE(
      torch::allclose(critic[1].weight.mm(critic[1].weight.t()), 2.0 * torch::eye(64), 1e-4, 1e-4));
  // Heads: gain 0.01 (action) and 1 (value), one row each.
  EXPECT_NEAR(actor.back().weight.norm().item<double>(), 0.01, 1e-6);
  EXPECT_NEAR(critic.back().weight.norm().item<double>(), 1.0, 1e-5);
  for (const auto& layer : actor) EXPECT_EQ(layer.bias.abs().sum().item<float>(), 0.0f);
  for (const auto& layer : critic) EXPECT_EQ(layer.bias.abs().sum().item<float>(), 0.0f);
  EXPECT_EQ(policy.log_std().abs().sum().item<float>(), 0.0f);
}

TEST(ActorCritic, SeedDeterminesTheInitialisation) {
  const ActorCritic a(4, 1, PolicyConfig{}, 1);
  const ActorCritic b(4, 1, PolicyConfig{}, 1);
  const ActorCritic c(4, 1, PolicyConfig{}, 2);
  EXPECT_TRUE(torch::equal(a.flat_parameters(), b.flat_parameters()));
  EXPECT_FALSE(torch::equal(a.flat_parameters(), c.flat_parameters()));
}

TEST(ActorCritic, GradientsAccumulateIntoTheFlatBuffer) {
  ActorCritic policy(3, 2, small_config(), 0);
  const torch::Tensor observations = torch::randn({5, 3});
  policy.zero_gradients();
  policy.value(observations).sum().backward();
  const torch::Tensor& gradients = policy.flat_gradients();
  const std::int64_t actor_size = (16 * 3 + 16) + (8 * 16 + 8) + (2 * 8 + 2);
  const std::int64_t critic_size = (12 * 3 + 12) + 13;
  EXPECT_EQ(gradients.narrow(0, 0, actor_size).abs().sum().item<float>(), 0.0f);
  EXPECT_GT(gradients.narrow(0, actor_size, critic_size).abs().sum().item<float>(), 0.0f);
  // The value head bias gradient is the batch size.
  EXPECT_FLOAT_EQ(gradients[actor_size + critic_size - 1].item<float>(), 5.0f);
  policy.zero_gradients();
  EXPECT_EQ(gradients.abs().sum().item<float>(), 0.0f);
  // A second backward accumulates into the same storage (it was not replaced).
  policy.value(observations).sum().backward();
  EXPECT_FLOAT_EQ(policy.flat_gradients()[actor_size + critic_size - 1].item<float>(), 5.0f);
}

TEST(ActorCritic, WritingFlatParametersChangesTheModel) {
  ActorCritic policy(3, 2, small_config(), 0);
  torch::NoGradGuard no_grad;
  policy.flat_parameters().fill_(0.0f);
  const torch::Tensor value = policy.value(torch::ones({1, 3}));
  EXPECT_EQ(value.item<float>(), 0.0f);
}

TEST(ActorCritic, LogProbabilityAndEntropyOfTheDiagonalGaussian) {
  PolicyConfig config = small_config();
  config.log_std_init = std::log(0.5);
  const ActorCritic policy(3, 2, config, 0);
  const torch::Tensor observations = torch::randn({4, 3});
  const torch::Tensor mean = policy.action_mean(observations).detach();
  const torch::Tensor actions = mean + torch::tensor({{0.5f, -1.0f}});
  const ActionEvaluation evaluation = policy.evaluate_actions(observations, actions);
  // z = (0.5/0.5, −1/0.5) = (1, −2): log p = −½(1 + 4) − 2·log 0.5 − log 2π.
  const double expected = -2.5 - 2 * std::log(0.5) - std::log(2 * M_PI);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(evaluation.log_prob[i].item<double>(), expected, 1e-5);
  // Entropy of N(μ, σ²) per component: ½ + ½log 2π + log σ.
  EXPECT_NEAR(evaluation.entropy.item<double>(),
              2 * (0.5 + 0.5 * std::log(2 * M_PI) + std::log(0.5)), 1e-5);
}

TEST(PolicyInference, MatchesTheDifferentiableForward) {
  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    PolicyConfig config = small_config();
    config.activation = activation;
    const ActorCritic policy(3, 2, config, 5);
    PolicyInference inference(policy, 4);
    const torch::Tensor observations = torch::randn({4, 3});
    inference.run({observations.data_ptr<float>(), 12});
    const torch::Tensor mean = policy.action_mean(observations).detach();
    const torch::Tensor value = policy.value(observations).detach();
    for (int i = 0; i < 8; ++i) {
      EXPECT_NEAR(inference.means()[i], mean.view({-1})[i].item<float>(), 1e-6);
    }
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(inference.values()[i], value[i].item<float>(), 1e-6);
    const std::vector<float> wrong(5);
    EXPECT_THROW(inference.run(wrong), std::invalid_argument);
  }
}

}  // namespace
}  // namespace upkie_rl

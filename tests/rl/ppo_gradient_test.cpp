#include "rl/ppo/ppo_gradient.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "rl/point_mass_vector_env.hpp"
#include "rl/ppo/autograd_ppo_gradient.hpp"
#include "rl/ppo/flat_adam.hpp"
#include "rl/ppo/ppo.hpp"
#include "rl/ppo/ppo_loss.hpp"

namespace upkie_rl {
namespace {

// One comparison of PpoGradient with autograd through compute_ppo_loss.
struct GradientCase {
  std::string name;
  std::int64_t observation_size = 4;
  std::int64_t action_size = 1;
  std::vector<std::int64_t> actor_hidden{64, 64};
  std::vector<std::int64_t> critic_hidden{64, 64};
  Activation activation = Activation::kReLU;
  double clip_range_vf = 0.2;
  bool normalize_advantage = true;
  double ent_coef = 0.0;
  // Standard deviation of old_log_prob − log π: 0.3 puts about half the ratios outside
  // 1 ± 0.2, 0.01 none.
  double log_prob_noise = 0.3;
  // Samples in the minibatch, and the most PpoGradient is sized for.
  std::int64_t batch = 128;
  std::int64_t max_batch = 128;
};

std::ostream& operator<<(std::ostream& out, const GradientCase& c) { return out << c.name; }

// A policy with every parameter away from its initial value (non-zero biases, log σ of
// both signs), so that each term of the gradient matters.
std::unique_ptr<ActorCritic> random_policy(const GradientCase& c, std::uint64_t seed) {
  PolicyConfig config;
  config.actor_hidden_sizes = c.actor_hidden;
  config.critic_hidden_sizes = c.critic_hidden;
  config.activation = c.activation;
  auto policy = std::make_unique<ActorCritic>(c.observation_size, c.action_size, config, seed);
  torch::NoGradGuard no_grad;
  at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(seed + 100);
  torch::Tensor& parameters = policy->flat_parameters();
  parameters.add_(0.1 * torch::randn(parameters.sizes(), generator));
  // The action head starts with gain 0.01: scale it up so the actor's gradient is not tiny.
  policy->actor_layers().back().weight.mul_(20.0);
  policy->log_std().copy_(torch::rand({c.action_size}, generator) - 0.5);
  return policy;
}

// Random observations; actions drawn from the policy; old log-probabilities and values
// near the current ones (values ±0.3 so that clipping at 0.2 bites for some samples).
PpoMinibatch random_minibatch(const ActorCritic& policy, const GradientCase& c,
                              std::uint64_t seed) {
  torch::NoGradGuard no_grad;
  at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(seed);
  const std::int64_t n = c.batch;
  PpoMinibatch batch;
  batch.observations = torch::randn({n, c.observation_size}, generator);
  const torch::Tensor mean = policy.action_mean(batch.observations);
  batch.actions = mean + torch::exp(policy.log_std()) * torch::randn(mean.sizes(), generator);
  const ActionEvaluation evaluation = policy.evaluate_actions(batch.observations, batch.actions);
  batch.old_log_prob = evaluation.log_prob + c.log_prob_noise * torch::randn({n}, generator);
  batch.old_values = evaluation.values + 0.3 * torch::randn({n}, generator);
  batch.advantages = 0.5 + 2.0 * torch::randn({n}, generator);
  batch.returns = batch.old_values + torch::randn({n}, generator);
  return batch;
}

PpoConfig ppo_config(const GradientCase& c) {
  PpoConfig config;
  config.clip_range = 0.2;
  config.clip_range_vf = c.clip_range_vf;
  config.normalize_advantage = c.normalize_advantage;
  config.ent_coef = c.ent_coef;
  config.vf_coef = 0.5;
  return config;
}

// ‖a − b‖/‖b‖ over [begin, end); 0 when both are zero (a clipped value has no gradient),
// NaN when a has NaNs.
double relative_error(const torch::Tensor& a, const torch::Tensor& b, std::int64_t begin,
                      std::int64_t end) {
  const torch::Tensor x = a.slice(0, begin, end).to(torch::kFloat64);
  const torch::Tensor y = b.slice(0, begin, end).to(torch::kFloat64);
  return (x - y).norm().item<double>() / std::max(y.norm().item<double>(), 1e-30);
}

// The reference: the loss on `batch` and its gradient by the loss's own backward pass.
// Checks on the way that the trainer's autograd path (autograd_ppo_gradient) computes
// exactly these.
std::pair<PpoLoss, torch::Tensor> reference_gradient(ActorCritic& policy, const PpoMinibatch& batch,
                                                     const PpoConfig& config) {
  policy.zero_gradients();
  const PpoLoss loss =
      compute_ppo_loss(policy.evaluate_actions(batch.observations, batch.actions), batch, config);
  loss.total.backward();
  const torch::Tensor expected = policy.flat_gradients().clone();
  policy.flat_gradients().fill_(std::numeric_limits<float>::quiet_NaN());
  const PpoLossStatistics autograd = autograd_ppo_gradient(view_minibatch(batch), policy, config);
  EXPECT_TRUE(torch::equal(policy.flat_gradients(), expected));
  EXPECT_EQ(autograd.total, loss.total.item<double>());
  EXPECT_EQ(autograd.approx_kl, loss.approx_kl.item<double>());
  EXPECT_EQ(autograd.clip_fraction, loss.clip_fraction.item<double>());
  return {loss, expected};
}

// Checks PpoGradient against autograd on `batch`, with `gradient` possibly used before.
void expect_same_as_autograd(PpoGradient& gradient, ActorCritic& policy, const PpoMinibatch& batch,
                             const PpoConfig& config) {
  const auto [loss, expected] = reference_gradient(policy, batch, config);

  // NaN everywhere: any entry compute() does not overwrite fails the comparison.
  policy.flat_gradients().fill_(std::numeric_limits<float>::quiet_NaN());
  const PpoLossStatistics statistics = gradient.compute(view_minibatch(batch), policy, config);
  const torch::Tensor actual = policy.flat_gradients().clone();

  // The whole vector, then each part on its own so that a wrong small part (log σ is one
  // value per action component) is not hidden by the larger ones.
  const ActorCriticLayout layout =
      actor_critic_layout(policy.observation_size(), policy.action_size(),
                          policy.config().actor_hidden_sizes, policy.config().critic_hidden_sizes);
  const std::int64_t critic_begin = layout.critic.front().weight;
  EXPECT_LT(relative_error(actual, expected, 0, layout.size), 1e-4);
  EXPECT_LT(relative_error(actual, expected, 0, critic_begin), 1e-4) << "actor";
  EXPECT_LT(relative_error(actual, expected, critic_begin, layout.log_std), 1e-4) << "critic";
  EXPECT_LT(relative_error(actual, expected, layout.log_std, layout.size), 1e-4) << "log σ";
  for (const auto* network : {&layout.actor, &layout.critic}) {
    for (const DenseLayerLayout& layer : *network) {
      EXPECT_LT(relative_error(actual, expected, layer.bias, layer.bias + layer.out), 1e-4)
          << "bias at " << layer.bias;
    }
  }

  EXPECT_NEAR(statistics.total, loss.total.item<double>(), 1e-5);
  EXPECT_NEAR(statistics.policy_gradient_loss, loss.policy_gradient_loss.item<double>(), 1e-5);
  EXPECT_NEAR(statistics.value_loss, loss.value_loss.item<double>(), 1e-5);
  EXPECT_NEAR(statistics.entropy_loss, loss.entropy_loss.item<double>(), 1e-5);
  EXPECT_NEAR(statistics.approx_kl, loss.approx_kl.item<double>(), 1e-5);
  EXPECT_NEAR(statistics.clip_fraction, loss.clip_fraction.item<double>(), 1e-5);
}

const char* kernel_name(PpoGradientKernel kernel) {
  return kernel == PpoGradientKernel::kFastest ? "fastest" : "portable";
}

// Both kernels, whatever the CPU (kFastest is the AVX2 one where the CPU has AVX2 and FMA).
constexpr PpoGradientKernel kKernels[] = {PpoGradientKernel::kFastest,
                                          PpoGradientKernel::kPortable};

class PpoGradientTest
    : public ::testing::TestWithParam<std::tuple<GradientCase, PpoGradientKernel>> {};

TEST_P(PpoGradientTest, EqualsTheAutogradGradientOfThePpoLoss) {
  const auto& [c, kernel] = GetParam();
  const std::unique_ptr<ActorCritic> owner = random_policy(c, 7);
  ActorCritic& policy = *owner;
  const PpoMinibatch batch = random_minibatch(policy, c, 11);
  const PpoConfig config = ppo_config(c);

  // The data exercise what the case says they do.
  {
    torch::NoGradGuard no_grad;
    const PpoLoss loss =
        compute_ppo_loss(policy.evaluate_actions(batch.observations, batch.actions), batch, config);
    const double clip_fraction = loss.clip_fraction.item<double>();
    if (c.log_prob_noise > 0.1) {
      EXPECT_GT(clip_fraction, 0.1);
      EXPECT_LT(clip_fraction, 0.9);
    } else {
      EXPECT_EQ(clip_fraction, 0.0);
    }
    const torch::Tensor change = (policy.value(batch.observations) - batch.old_values).abs();
    const double values_clipped = (change > 0.2).to(torch::kFloat64).mean().item<double>();
    EXPECT_GT(values_clipped, 0.1);
    EXPECT_LT(values_clipped, 0.9);
  }

  PpoGradient gradient(policy, c.max_batch, kernel);
  expect_same_as_autograd(gradient, policy, batch, config);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PpoGradientTest,
    ::testing::Combine(
        ::testing::Values(
            GradientCase{.name = "pendulum_relu"},
            GradientCase{.name = "tanh", .activation = Activation::kTanh},
            GradientCase{.name = "no_value_clipping", .clip_range_vf = 0.0},
            GradientCase{.name = "tanh_no_value_clipping",
                         .activation = Activation::kTanh,
                         .clip_range_vf = 0.0},
            GradientCase{.name = "raw_advantages", .normalize_advantage = false},
            GradientCase{.name = "entropy_bonus", .ent_coef = 0.01},
            GradientCase{.name = "tanh_entropy_raw_advantages",
                         .activation = Activation::kTanh,
                         .normalize_advantage = false,
                         .ent_coef = 0.01},
            GradientCase{.name = "ratios_inside_the_clip_range", .log_prob_noise = 0.01},
            GradientCase{.name = "last_minibatch_smaller", .batch = 37, .max_batch = 128},
            GradientCase{.name = "other_shapes_relu",
                         .observation_size = 5,
                         .action_size = 3,
                         .actor_hidden = {16, 8},
                         .critic_hidden = {12},
                         .ent_coef = 0.01,
                         .batch = 50,
                         .max_batch = 64},
            // Layers one unit wide take the kernels' one-column paths.
            GradientCase{.name = "one_unit_layers_relu",
                         .observation_size = 3,
                         .action_size = 2,
                         .actor_hidden = {1, 5},
                         .critic_hidden = {1},
                         .batch = 40,
                         .max_batch = 40},
            GradientCase{.name = "one_unit_layers_tanh",
                         .observation_size = 3,
                         .action_size = 2,
                         .actor_hidden = {1, 5},
                         .critic_hidden = {1},
                         .activation = Activation::kTanh,
                         .batch = 40,
                         .max_batch = 40},
            GradientCase{.name = "other_shapes_tanh",
                         .observation_size = 5,
                         .action_size = 3,
                         .actor_hidden = {16, 8},
                         .critic_hidden = {12},
                         .activation = Activation::kTanh,
                         .clip_range_vf = 0.0,
                         .normalize_advantage = false,
                         .batch = 64,
                         .max_batch = 64}),
        ::testing::ValuesIn(kKernels)),
    [](const ::testing::TestParamInfo<PpoGradientTest::ParamType>& info) {
      return std::get<0>(info.param).name + "_" + kernel_name(std::get<1>(info.param));
    });

// The training loop: one PpoGradient, full minibatches then a smaller last one, all
// slices of one shuffled rollout.
TEST(PpoGradient, ReusedAcrossMinibatchesOfDecreasingSize) {
  const GradientCase c{.name = "rollout", .activation = Activation::kTanh, .batch = 300};
  const std::unique_ptr<ActorCritic> owner = random_policy(c, 3);
  ActorCritic& policy = *owner;
  const PpoMinibatch rollout = random_minibatch(policy, c, 5);
  const PpoConfig config = ppo_config(c);
  for (const PpoGradientKernel kernel : kKernels) {
    PpoGradient gradient(policy, 128, kernel);
    const std::pair<std::int64_t, std::int64_t> slices[] = {{0, 128}, {128, 128}, {256, 44}};
    for (const auto& [begin, length] : slices) {
      SCOPED_TRACE(std::string(kernel_name(kernel)) + ", rows " + std::to_string(begin) + " + " +
                   std::to_string(length));
      const PpoMinibatch batch{rollout.observations.narrow(0, begin, length),
                               rollout.actions.narrow(0, begin, length),
                               rollout.old_log_prob.narrow(0, begin, length),
                               rollout.old_values.narrow(0, begin, length),
                               rollout.advantages.narrow(0, begin, length),
                               rollout.returns.narrow(0, begin, length)};
      expect_same_as_autograd(gradient, policy, batch, config);
      // The view of the whole rollout sliced the way Ppo::update() does is the same batch.
      const PpoMinibatchView rows = view_minibatch(rollout).rows(begin, length);
      EXPECT_EQ(rows.size, length);
      EXPECT_EQ(rows.observations.data(), batch.observations.data_ptr<float>());
      EXPECT_EQ(rows.observations.size(), static_cast<std::size_t>(length * c.observation_size));
      EXPECT_EQ(rows.returns.data(), batch.returns.data_ptr<float>());
    }
  }
}

// One sample: the advantage is not normalised (compute_ppo_loss needs two or more).
TEST(PpoGradient, SingleSampleMinibatch) {
  // With value clipping the sample's value happens to be clipped (no critic gradient).
  for (const double clip_range_vf : {0.2, 0.0}) {
    SCOPED_TRACE("clip_range_vf " + std::to_string(clip_range_vf));
    const GradientCase c{.name = "single", .clip_range_vf = clip_range_vf, .batch = 1};
    const std::unique_ptr<ActorCritic> owner = random_policy(c, 13);
    ActorCritic& policy = *owner;
    const PpoMinibatch batch = random_minibatch(policy, c, 17);
    for (const PpoGradientKernel kernel : kKernels) {
      SCOPED_TRACE(kernel_name(kernel));
      PpoGradient gradient(policy, 128, kernel);
      expect_same_as_autograd(gradient, policy, batch, ppo_config(c));
    }
  }
}

// Values exactly at the clipping bounds: torch's clamp passes the gradient there. The
// critic's head is set to output exactly 0.5 and the bound is 0.25, so V − V_old is exactly
// ±0.25 (at a bound), ±0.5 (clipped) or 0.
TEST(PpoGradient, ValueClippingBoundsPassTheGradientLikeTorch) {
  const GradientCase c{.name = "bounds", .clip_range_vf = 0.25, .batch = 50};
  const std::unique_ptr<ActorCritic> owner = random_policy(c, 21);
  ActorCritic& policy = *owner;
  {
    torch::NoGradGuard no_grad;
    policy.critic_layers().back().weight.zero_();
    policy.critic_layers().back().bias.fill_(0.5);
  }
  PpoMinibatch batch = random_minibatch(policy, c, 23);
  const float changes[] = {0.25f, -0.25f, 0.5f, -0.5f, 0.0f};
  batch.old_values = torch::empty({c.batch});
  for (std::int64_t i = 0; i < c.batch; ++i) {
    batch.old_values[i] = 0.5f - changes[i % 5];
  }
  batch.returns = batch.old_values + torch::randn({c.batch});
  const torch::Tensor change = policy.value(batch.observations).detach() - batch.old_values;
  ASSERT_EQ((change.abs() == 0.25f).sum().item<std::int64_t>(), 20);

  for (const PpoGradientKernel kernel : kKernels) {
    SCOPED_TRACE(kernel_name(kernel));
    PpoGradient gradient(policy, c.batch, kernel);
    expect_same_as_autograd(gradient, policy, batch, ppo_config(c));
  }
}

// Ppo::update() with the hand-written gradient against the same update by autograd
// (ppo.gradient: autograd, what Ppo::update did before PpoGradient): same permutations,
// minibatches, clipping and Adam steps on the same rollout. The parameters after a whole
// update (45 Adam steps) differ by float rounding only.
TEST(PpoGradient, PpoUpdateMatchesTheAutogradUpdate) {
  TrainingConfig config;
  config.env_id = "point-mass";
  config.num_envs = 4;
  config.policy.actor_hidden_sizes = {32, 32};
  config.policy.critic_hidden_sizes = {32, 32};
  config.ppo.n_steps = 512;
  config.ppo.batch_size = 60;  // 8 full minibatches and one of 32 per epoch
  config.ppo.n_epochs = 5;
  config.ppo.learning_rate_initial = 1e-3;
  config.seed = 3;
  for (const Activation activation : {Activation::kReLU, Activation::kTanh}) {
    SCOPED_TRACE(activation_name(activation));
    config.policy.activation = activation;
    config.ppo.gradient = GradientMethod::kHand;
    TrainingConfig autograd_config = config;
    autograd_config.ppo.gradient = GradientMethod::kAutograd;
    testing::PointMassVectorEnv env_a(4), env_b(4);
    Ppo ppo(env_a, config), reference(env_b, autograd_config);
    ASSERT_TRUE(ppo.uses_hand_gradient());
    ASSERT_FALSE(reference.uses_hand_gradient());
    ppo.reset_environments(1);
    reference.reset_environments(1);
    ppo.collect_rollout();
    reference.collect_rollout();
    const torch::Tensor initial = ppo.policy().flat_parameters().clone();
    ASSERT_TRUE(torch::equal(initial, reference.policy().flat_parameters()));

    const PpoUpdateStatistics expected = reference.update();
    const PpoUpdateStatistics statistics = ppo.update();
    EXPECT_EQ(ppo.optimizer().step_count(), 45);
    EXPECT_EQ(reference.optimizer().step_count(), 45);
    const torch::Tensor step = (reference.policy().flat_parameters() - initial).to(torch::kFloat64);
    const torch::Tensor difference =
        (ppo.policy().flat_parameters() - reference.policy().flat_parameters()).to(torch::kFloat64);
    ASSERT_GT(step.norm().item<double>(), 1e-5);
    EXPECT_LT(difference.norm().item<double>() / step.norm().item<double>(), 1e-5);
    EXPECT_NEAR(statistics.loss, expected.loss, 1e-4 * std::max(1.0, std::abs(expected.loss)));
    EXPECT_NEAR(statistics.approx_kl, expected.approx_kl, 1e-6);
    EXPECT_NEAR(statistics.value_loss, expected.value_loss,
                1e-4 * std::max(1.0, std::abs(expected.value_loss)));
  }
}

// Every activation the backward pass does not know is refused, not treated as another one;
// a policy differing only by its activation is "another policy".
TEST(PpoGradient, RefusesActivationsItDoesNotCover) {
  EXPECT_TRUE(PpoGradient::covers(Activation::kReLU));
  EXPECT_TRUE(PpoGradient::covers(Activation::kTanh));
  for (const Activation activation : all_activations()) {
    if (activation == Activation::kReLU || activation == Activation::kTanh) continue;
    SCOPED_TRACE(activation_name(activation));
    EXPECT_FALSE(PpoGradient::covers(activation));
    const GradientCase c{.name = activation_name(activation), .activation = activation};
    const std::unique_ptr<ActorCritic> policy = random_policy(c, 1);
    try {
      PpoGradient gradient(*policy, 8);
      FAIL() << "expected the policy to be refused";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(std::string("not ") + activation_name(activation)),
                std::string::npos)
          << error.what();
    }
  }

  const GradientCase relu{.name = "relu"};
  const GradientCase tanh{.name = "tanh", .activation = Activation::kTanh};
  const std::unique_ptr<ActorCritic> relu_policy = random_policy(relu, 1);
  const std::unique_ptr<ActorCritic> tanh_policy = random_policy(tanh, 1);
  const PpoMinibatch relu_batch = random_minibatch(*relu_policy, relu, 2);
  const PpoConfig config = ppo_config(relu);
  PpoGradient gradient(*relu_policy, 128);
  EXPECT_NO_THROW(gradient.compute(view_minibatch(relu_batch), *relu_policy, config));
  EXPECT_THROW(gradient.compute(view_minibatch(relu_batch), *tanh_policy, config),
               std::invalid_argument);
}

// The PPO loss on `batch` with the policy's parameters moved by `step` (then restored).
double loss_at(ActorCritic& policy, const PpoMinibatch& batch, const PpoConfig& config,
               const torch::Tensor& step) {
  torch::NoGradGuard no_grad;
  policy.flat_parameters().add_(step);
  const double loss =
      compute_ppo_loss(policy.evaluate_actions(batch.observations, batch.actions), batch, config)
          .total.item<double>();
  policy.flat_parameters().sub_(step);
  return loss;
}

// The gradient the trainer uses for every activation (autograd_ppo_gradient, the fallback
// of ppo.gradient auto) equals the loss's own backward pass and agrees with central
// differences of the loss along the gradient and along a random direction: the gradient
// is the derivative of the forward pass whatever the activation (whose values
// tests/rl/actor_critic_test.cpp compares with policy/activation.cpp's). Ratios inside
// the clip range and no value clipping keep the loss smooth around the point.
TEST(PpoGradient, TheAutogradGradientIsTheLossDerivativeForEveryActivation) {
  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    const GradientCase c{.name = activation_name(activation),
                         .actor_hidden = {16, 16},
                         .critic_hidden = {16},
                         .activation = activation,
                         .clip_range_vf = 0.0,
                         .ent_coef = 0.01,
                         .log_prob_noise = 0.01};
    const std::unique_ptr<ActorCritic> owner = random_policy(c, 4);
    ActorCritic& policy = *owner;
    const PpoMinibatch batch = random_minibatch(policy, c, 6);
    const PpoConfig config = ppo_config(c);

    const auto [loss, gradient] = reference_gradient(policy, batch, config);
    EXPECT_EQ(loss.clip_fraction.item<double>(), 0.0);

    const double norm = gradient.to(torch::kFloat64).norm().item<double>();
    ASSERT_GT(norm, 1e-3);
    at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(9);
    const torch::Tensor random = torch::randn(gradient.sizes(), generator);
    for (const torch::Tensor& direction : {gradient / norm, random / random.norm()}) {
      constexpr double kStep = 1e-3;
      const double slope = (loss_at(policy, batch, config, kStep * direction) -
                            loss_at(policy, batch, config, -kStep * direction)) /
                           (2.0 * kStep);
      const double predicted = (gradient * direction).sum().item<double>();
      EXPECT_NEAR(slope, predicted, 0.02 * norm) << "norm " << norm;
    }
  }
}

TEST(PpoGradient, KernelChoice) {
  const GradientCase c{.name = "kernel"};
  const std::unique_ptr<ActorCritic> policy = random_policy(c, 1);
  EXPECT_FALSE(PpoGradient(*policy, 8, PpoGradientKernel::kPortable).uses_avx2());
#if defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  EXPECT_EQ(PpoGradient(*policy, 8).uses_avx2(), avx2);
#endif
}

TEST(PpoGradient, RejectsOversizedBatchesAndOtherPolicies) {
  const GradientCase c{.name = "errors", .batch = 65};
  const std::unique_ptr<ActorCritic> owner = random_policy(c, 1);
  ActorCritic& policy = *owner;
  const PpoMinibatch batch = random_minibatch(policy, c, 2);
  const PpoConfig config = ppo_config(c);
  PpoGradient gradient(policy, 64);
  EXPECT_THROW(gradient.compute(view_minibatch(batch), policy, config), std::invalid_argument);
  EXPECT_NO_THROW(gradient.compute(view_minibatch(batch).rows(0, 64), policy, config));
  EXPECT_THROW(gradient.compute(view_minibatch(batch).rows(0, 0), policy, config),
               std::invalid_argument);

  GradientCase wider = c;
  wider.actor_hidden = {64, 32};
  const std::unique_ptr<ActorCritic> other = random_policy(wider, 1);
  EXPECT_THROW(gradient.compute(view_minibatch(batch).rows(0, 64), *other, config),
               std::invalid_argument);

  PpoMinibatchView short_actions = view_minibatch(batch).rows(0, 64);
  short_actions.actions = short_actions.actions.first(10);
  EXPECT_THROW(gradient.compute(short_actions, policy, config), std::invalid_argument);

  PpoMinibatch doubles = batch;
  doubles.returns = batch.returns.to(torch::kFloat64);
  EXPECT_THROW(view_minibatch(doubles), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl

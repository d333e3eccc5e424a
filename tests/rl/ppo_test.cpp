#include "rl/ppo/ppo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "rl/point_mass_config.hpp"
#include "rl/point_mass_vector_env.hpp"

namespace upkie_rl {
namespace {

using testing::point_mass_config;
using testing::PointMassVectorEnv;

// Mean return over `episodes` episodes of the deterministic policy, or of uniformly random
// actions when `policy` is null.
double evaluate(const ActorCritic* policy, int episodes, std::uint64_t seed) {
  PointMassVectorEnv env(1);
  std::span<const float> observation = env.reset(seed);
  std::vector<float> x(observation.begin(), observation.end());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  double total = 0.0;
  int finished = 0;
  while (finished < episodes) {
    float action = uniform(rng);
    if (policy != nullptr) {
      torch::NoGradGuard no_grad;
      action = std::clamp(policy->action_mean(torch::tensor({{x[0]}})).item<float>(), -1.0f, 1.0f);
    }
    const VectorStep& step = env.step(std::span<const float>(&action, 1));
    if (step.terminated[0] || step.truncated[0]) {
      total += step.episode_returns[0];
      ++finished;
    }
    x[0] = step.observations[0];
  }
  return total / episodes;
}

// Trains `ppo` to its total timesteps on the point mass and checks that it learned.
void expect_training_improves_the_return(Ppo& ppo) {
  ppo.reset_environments(3);
  const double random_return = evaluate(nullptr, 40, 99);
  const double initial_return = evaluate(&ppo.policy(), 40, 99);
  while (ppo.num_timesteps() < ppo.config().ppo.total_timesteps) ppo.iterate();
  const double trained_return = evaluate(&ppo.policy(), 40, 99);
  // A perfect controller scores close to 50 − Σx² ≈ 47; random actions about 30.
  EXPECT_GT(trained_return, random_return + 8.0)
      << "random " << random_return << ", initial " << initial_return;
  EXPECT_GT(trained_return, initial_return + 5.0);
  EXPECT_GT(ppo.episodes().mean_return(), random_return);
  EXPECT_EQ(ppo.num_timesteps(), ppo.iterations() * 512);
}

TEST(Ppo, TrainingImprovesTheReturnOverARandomPolicy) {
  PointMassVectorEnv env(4);
  Ppo ppo(env, point_mass_config());
  EXPECT_TRUE(ppo.uses_hand_gradient());
  expect_training_improves_the_return(ppo);
}

// An ELU network, which the hand-written gradient does not cover: ppo.gradient auto
// trains it with autograd, and it learns; ppo.gradient hand refuses it.
TEST(Ppo, AnEluNetworkTrainsThroughAutograd) {
  TrainingConfig config = point_mass_config();
  config.policy.activation = Activation::kELU;
  PointMassVectorEnv env(4);
  Ppo ppo(env, config);
  EXPECT_FALSE(ppo.uses_hand_gradient());
  expect_training_improves_the_return(ppo);

  config.ppo.gradient = GradientMethod::kHand;
  PointMassVectorEnv other(4);
  EXPECT_THROW(Ppo(other, config), std::invalid_argument);
}

// ppo.gradient auto uses the hand-written gradient where it covers the activation and
// autograd elsewhere. The two paths sum in different orders, so that an update's last bits
// tell which one ran: with auto, the update must be bit for bit that of the path auto
// stands for, and for relu and tanh differ in its last bits from autograd's while agreeing
// with it closely (the gradients themselves are compared in tests/rl/ppo_gradient_test.cpp).
// Odd layer widths, so that the kernels' tails run too.
TEST(Ppo, AutoTakesTheHandGradientWhereItCoversTheActivationAndAutogradElsewhere) {
  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    TrainingConfig config = point_mass_config();
    config.policy.activation = activation;
    config.policy.actor_hidden_sizes = {7, 5};
    config.policy.critic_hidden_sizes = {9};
    // The parameters after one iteration with `method`, and whether it ran the hand path.
    const auto update = [&config](GradientMethod method) {
      TrainingConfig method_config = config;
      method_config.ppo.gradient = method;
      PointMassVectorEnv env(4);
      Ppo ppo(env, method_config);
      ppo.reset_environments(2);
      const torch::Tensor initial = ppo.policy().flat_parameters().clone();
      ppo.iterate();
      const torch::Tensor after = ppo.policy().flat_parameters().clone();
      EXPECT_GT((after - initial).norm().item<double>(), 1e-4);
      return std::pair{after, ppo.uses_hand_gradient()};
    };
    const auto [with_auto, auto_used_hand] = update(GradientMethod::kAuto);
    const auto [with_autograd, autograd_used_hand] = update(GradientMethod::kAutograd);
    EXPECT_FALSE(autograd_used_hand);
    const bool covered = activation == Activation::kReLU || activation == Activation::kTanh;
    EXPECT_EQ(auto_used_hand, covered);
    if (covered) {
      const auto [with_hand, hand_used_hand] = update(GradientMethod::kHand);
      EXPECT_TRUE(hand_used_hand);
      EXPECT_TRUE(torch::equal(with_auto, with_hand));
      EXPECT_FALSE(torch::equal(with_auto, with_autograd));
      EXPECT_LT((with_auto - with_autograd).abs().max().item<double>(), 1e-4);
    } else {
      EXPECT_TRUE(torch::equal(with_auto, with_autograd));
      config.ppo.gradient = GradientMethod::kHand;
      PointMassVectorEnv env(4);
      EXPECT_THROW(Ppo(env, config), std::invalid_argument);
    }
  }
}

TEST(Ppo, SameSeedGivesTheSameRun) {
  TrainingConfig config = point_mass_config();
  config.ppo.total_timesteps = 2048;
  PointMassVectorEnv env_a(4), env_b(4);
  Ppo a(env_a, config), b(env_b, config);
  a.reset_environments(1);
  b.reset_environments(1);
  for (int i = 0; i < 3; ++i) {
    const PpoUpdateStatistics sa = a.iterate();
    const PpoUpdateStatistics sb = b.iterate();
    EXPECT_EQ(sa.loss, sb.loss);
    EXPECT_EQ(sa.approx_kl, sb.approx_kl);
  }
  EXPECT_TRUE(torch::equal(a.policy().flat_parameters(), b.policy().flat_parameters()));
}

TEST(Ppo, LearningRateFollowsTheLinearScheduleOncePerIteration) {
  TrainingConfig config = point_mass_config();
  config.ppo.total_timesteps = 2048;
  config.ppo.learning_rate_initial = 2e-4;
  config.ppo.learning_rate_final = 1e-5;
  PointMassVectorEnv env(4);
  Ppo ppo(env, config);
  ppo.reset_environments(0);
  for (int i = 1; i <= 3; ++i) {
    const PpoUpdateStatistics statistics = ppo.iterate();
    const double p = 1.0 - (512.0 * i) / 2048.0;
    EXPECT_DOUBLE_EQ(statistics.learning_rate, 1e-5 + p * (2e-4 - 1e-5));
    EXPECT_DOUBLE_EQ(ppo.optimizer().learning_rate(), statistics.learning_rate);
    EXPECT_EQ(statistics.n_updates, 5 * i);
    EXPECT_EQ(ppo.optimizer().step_count(), 5 * 8 * i);  // 8 minibatches of 64 per epoch
  }
}

// Two envs whose episodes last three steps. At the third step env 0 is both terminated and
// truncated (counts as terminated: no bootstrap) and env 1 is only truncated (bootstrap).
class ScriptedVectorEnv final : public VectorEnv {
 public:
  ScriptedVectorEnv() {
    space_.low = {-10.0f};
    space_.high = {10.0f};
    space_.names = {"s"};
    result_.observations = {0.0f, 0.0f};
    result_.rewards = {1.0f, 1.0f};
    result_.terminated = {0, 0};
    result_.truncated = {0, 0};
    result_.final_observations = {0.0f, 0.0f};
    result_.episode_returns = {0.0, 0.0};
    result_.episode_lengths = {0, 0};
  }
  std::size_t num_envs() const override { return 2; }
  const BoxSpace& observation_space() const override { return space_; }
  const BoxSpace& action_space() const override { return space_; }
  std::span<const float> reset(std::optional<std::uint64_t>) override {
    step_ = 0;
    result_.observations = {0.0f, 0.0f};
    return result_.observations;
  }
  const VectorStep& step(std::span<const float>) override {
    ++step_;
    const bool end = step_ % 3 == 0;
    result_.terminated = {end, 0};
    result_.truncated = {end, end};
    result_.final_observations = {end ? 4.0f : 0.0f, end ? 5.0f : 0.0f};
    result_.episode_returns = {3.0, 3.0};
    result_.episode_lengths = {3, 3};
    const float next = end ? 0.0f : 0.5f * static_cast<float>(step_ % 3);
    result_.observations = {next, next + 1.0f};
    return result_;
  }

 private:
  BoxSpace space_;
  VectorStep result_;
  int step_ = 0;
};

TEST(Ppo, TruncatedEpisodesBootstrapWithTheCurrentCriticTerminatedOnesDoNot) {
  ScriptedVectorEnv env;
  TrainingConfig config = point_mass_config(2);
  config.ppo.n_steps = 6;
  config.ppo.batch_size = 6;
  config.ppo.gamma = 0.9;
  Ppo ppo(env, config);
  ppo.reset_environments(0);
  ppo.collect_rollout();
  torch::Tensor rewards = ppo.buffer().flat_returns();  // to keep the buffer alive in scope
  RolloutBuffer& buffer = const_cast<RolloutBuffer&>(ppo.buffer());
  const float* step2_rewards = buffer.rewards(2);
  const float* step2_dones = buffer.dones(2);
  const double final_value = ppo.policy().value(torch::tensor({{5.0f}})).item<double>();
  EXPECT_FLOAT_EQ(step2_rewards[0], 1.0f);
  EXPECT_NEAR(step2_rewards[1], 1.0 + 0.9 * final_value, 1e-5);
  EXPECT_EQ(step2_dones[0], 1.0f);
  EXPECT_EQ(step2_dones[1], 1.0f);
  EXPECT_FLOAT_EQ(buffer.rewards(1)[1], 1.0f);
  EXPECT_EQ(buffer.dones(1)[1], 0.0f);
  EXPECT_EQ(ppo.episodes().total_episodes(), 2);
  EXPECT_DOUBLE_EQ(ppo.episodes().mean_return(), 3.0);
  EXPECT_DOUBLE_EQ(ppo.episodes().mean_length(), 3.0);
}

TEST(Ppo, ActionsAreSampledAroundTheMeanAndClippedForTheEnvOnly) {
  ScriptedVectorEnv env;
  TrainingConfig config = point_mass_config(2);
  config.ppo.n_steps = 600;
  config.ppo.batch_size = 60;
  config.policy.log_std_init = std::log(20.0);  // σ = 20: most samples outside ±10
  Ppo ppo(env, config);
  ppo.reset_environments(0);
  ppo.collect_rollout();
  const torch::Tensor actions = ppo.buffer().flat_actions();
  EXPECT_GT(actions.abs().max().item<float>(), 10.0f);  // stored unclipped
  EXPECT_NEAR(actions.std().item<double>(), 20.0, 2.0);
  // Stored log-probabilities are those of the stored (unclipped) actions.
  const ActionEvaluation evaluation =
      ppo.policy().evaluate_actions(ppo.buffer().flat_observations(), actions);
  EXPECT_TRUE(
      torch::allclose(evaluation.log_prob.detach(), ppo.buffer().flat_log_probs(), 1e-4, 1e-4));
  EXPECT_TRUE(torch::allclose(evaluation.values.detach(), ppo.buffer().flat_values(), 1e-5, 1e-5));
}

TEST(Ppo, RefusesAConfigThatDoesNotFitTheEnv) {
  PointMassVectorEnv env(4);
  TrainingConfig config = point_mass_config(3);
  EXPECT_THROW(Ppo(env, config), std::invalid_argument);
  config = point_mass_config(4);
  config.ppo.batch_size = 0;
  EXPECT_THROW(Ppo(env, config), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl

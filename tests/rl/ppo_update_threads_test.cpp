// ppo.update_threads: PpoGradient with the critic's part on a companion thread gives the
// gradient, the loss terms and the trained weights of one thread, bit for bit, and
// allocates nothing per minibatch.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/allocation_counter.hpp"
#include "rl/point_mass_vector_env.hpp"
#include "rl/ppo/ppo.hpp"
#include "rl/ppo/ppo_gradient.hpp"

namespace upkie_rl {
namespace {

// A policy with inputs and actions like the velocity task's (21, 6), hidden layers of odd
// widths (so that the kernels' tails run), and every parameter away from its initial value.
std::unique_ptr<ActorCritic> random_policy(Activation activation, std::uint64_t seed) {
  PolicyConfig config;
  config.actor_hidden_sizes = {128, 67};
  config.critic_hidden_sizes = {125, 45};
  config.activation = activation;
  auto policy = std::make_unique<ActorCritic>(21, 6, config, seed);
  torch::NoGradGuard no_grad;
  at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(seed + 100);
  policy->flat_parameters().add_(0.1 * torch::randn(policy->flat_parameters().sizes(), generator));
  policy->actor_layers().back().weight.mul_(20.0);  // so that the actor's gradient is not tiny
  policy->log_std().copy_(torch::rand({6}, generator) - 0.5);
  return policy;
}

// `n` random samples around the policy's own actions, log-probabilities and values, so that
// some ratios and values are clipped and others not.
PpoMinibatch random_minibatch(const ActorCritic& policy, std::int64_t n, std::uint64_t seed) {
  torch::NoGradGuard no_grad;
  at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(seed);
  PpoMinibatch batch;
  batch.observations = torch::randn({n, policy.observation_size()}, generator);
  const torch::Tensor mean = policy.action_mean(batch.observations);
  batch.actions = mean + torch::exp(policy.log_std()) * torch::randn(mean.sizes(), generator);
  const ActionEvaluation evaluation = policy.evaluate_actions(batch.observations, batch.actions);
  batch.old_log_prob = evaluation.log_prob + 0.3 * torch::randn({n}, generator);
  batch.old_values = evaluation.values + 0.3 * torch::randn({n}, generator);
  batch.advantages = 0.5 + 2.0 * torch::randn({n}, generator);
  batch.returns = batch.old_values + torch::randn({n}, generator);
  return batch;
}

// The flat gradient compute() writes, with NaN before it everywhere: an entry it does not
// overwrite stays NaN.
struct GradientResult {
  std::vector<float> gradient;
  PpoLossStatistics statistics;
};

GradientResult compute(PpoGradient& gradient, ActorCritic& policy, const PpoMinibatch& batch,
                       const PpoConfig& config) {
  policy.flat_gradients().fill_(std::numeric_limits<float>::quiet_NaN());
  GradientResult result;
  result.statistics = gradient.compute(view_minibatch(batch), policy, config);
  const float* data = policy.flat_gradients().data_ptr<float>();
  result.gradient.assign(data, data + policy.flat_gradients().numel());
  return result;
}

void expect_bit_identical(const GradientResult& two, const GradientResult& one) {
  ASSERT_EQ(two.gradient.size(), one.gradient.size());
  EXPECT_EQ(
      std::memcmp(two.gradient.data(), one.gradient.data(), one.gradient.size() * sizeof(float)),
      0);
  for (std::size_t i = 0; i < two.gradient.size(); ++i) {
    ASSERT_FALSE(std::isnan(two.gradient[i])) << "gradient entry " << i << " not written";
  }
  EXPECT_EQ(two.statistics.total, one.statistics.total);
  EXPECT_EQ(two.statistics.policy_gradient_loss, one.statistics.policy_gradient_loss);
  EXPECT_EQ(two.statistics.value_loss, one.statistics.value_loss);
  EXPECT_EQ(two.statistics.entropy_loss, one.statistics.entropy_loss);
  EXPECT_EQ(two.statistics.approx_kl, one.statistics.approx_kl);
  EXPECT_EQ(two.statistics.clip_fraction, one.statistics.clip_fraction);
}

// Random minibatches of decreasing sizes through one PpoGradient of each thread count, on
// both activations and both kernels, with and without the entropy term, advantage
// normalisation and value clipping. The largest minibatches keep both threads busy long
// enough to overlap, so that buffers shared by the two parts would show.
TEST(PpoUpdateThreads, ComputeIsBitIdenticalOnOneAndTwoThreads) {
  for (const Activation activation : {Activation::kTanh, Activation::kReLU}) {
    for (const PpoGradientKernel kernel :
         {PpoGradientKernel::kFastest, PpoGradientKernel::kPortable}) {
      SCOPED_TRACE(std::string(activation_name(activation)) +
                   (kernel == PpoGradientKernel::kPortable ? ", Eigen" : ", fastest kernel"));
      const std::unique_ptr<ActorCritic> policy = random_policy(activation, 4);
      PpoGradient one(*policy, 1024, kernel, 1);
      PpoGradient two(*policy, 1024, kernel, 2);
      ASSERT_EQ(one.update_threads(), 1);
      ASSERT_EQ(two.update_threads(), 2);
      PpoConfig config;
      std::uint64_t seed = 10;
      for (const std::int64_t rows : {1024, 1024, 777, 64, 1}) {
        for (const bool other_terms : {false, true}) {
          config.ent_coef = other_terms ? 0.01 : 0.0;
          config.normalize_advantage = !other_terms;
          config.clip_range_vf = other_terms ? 0.0 : 0.2;
          const PpoMinibatch batch = random_minibatch(*policy, rows, ++seed);
          const GradientResult with_one = compute(one, *policy, batch, config);
          const GradientResult with_two = compute(two, *policy, batch, config);
          SCOPED_TRACE(std::to_string(rows) + " rows");
          expect_bit_identical(with_two, with_one);
          EXPECT_NE(with_two.statistics.value_loss, 0.0);
          EXPECT_NE(with_two.statistics.policy_gradient_loss, 0.0);
        }
      }
    }
  }
}

// The trainer's use: a minibatch after another, allocating nothing on either thread.
TEST(PpoUpdateThreads, TwoThreadsAllocateNothingPerMinibatch) {
  const std::unique_ptr<ActorCritic> policy = random_policy(Activation::kTanh, 5);
  PpoGradient gradient(*policy, 256, PpoGradientKernel::kFastest, 2);
  const PpoMinibatch batch = random_minibatch(*policy, 256, 6);
  const PpoMinibatchView view = view_minibatch(batch);
  const PpoConfig config;
  gradient.compute(view, *policy, config);
  const std::size_t allocations = testing::all_threads_allocations.load();
  double total = 0.0;
  for (int i = 0; i < 20; ++i) total += gradient.compute(view.rows(i, 200), *policy, config).total;
  EXPECT_EQ(testing::all_threads_allocations.load(), allocations);
  EXPECT_TRUE(std::isfinite(total));
}

TEST(PpoUpdateThreads, OnlyOneAndTwoThreadsAreAccepted) {
  const std::unique_ptr<ActorCritic> policy = random_policy(Activation::kReLU, 7);
  for (const std::int64_t threads : {0, 3, -1}) {
    try {
      PpoGradient gradient(*policy, 8, PpoGradientKernel::kFastest, threads);
      ADD_FAILURE() << threads << " update threads were accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("ppo.update_threads"), std::string::npos)
          << error.what();
    }
  }
  EXPECT_EQ(PpoGradient(*policy, 8).update_threads(), 1);  // the class alone: one thread
}

TrainingConfig point_mass_config(Activation activation, std::int64_t update_threads) {
  TrainingConfig config;
  config.env_id = "point-mass";
  config.num_envs = 4;
  config.policy.actor_hidden_sizes = {32, 17};
  config.policy.critic_hidden_sizes = {24, 9};
  config.policy.activation = activation;
  config.ppo.total_timesteps = 2048;
  config.ppo.n_steps = 512;
  config.ppo.batch_size = 100;  // the last minibatch of each epoch is smaller (12)
  config.ppo.n_epochs = 3;
  config.ppo.ent_coef = 0.001;
  config.ppo.update_threads = update_threads;
  config.seed = 11;
  return config;
}

// A short training: the weights, the optimiser's moments and the logged losses after each
// iteration are the same bit for bit with one update thread and with two.
TEST(PpoUpdateThreads, TrainingIsBitIdenticalOnOneAndTwoThreads) {
  EXPECT_EQ(TrainingConfig().ppo.update_threads, 2);  // the default
  for (const Activation activation : {Activation::kTanh, Activation::kReLU}) {
    SCOPED_TRACE(activation_name(activation));
    testing::PointMassVectorEnv env_one(4), env_two(4);
    Ppo one(env_one, point_mass_config(activation, 1));
    Ppo two(env_two, point_mass_config(activation, 2));
    ASSERT_EQ(one.update_threads(), 1);
    ASSERT_EQ(two.update_threads(), 2);
    const torch::Tensor initial = one.policy().flat_parameters().clone();
    one.reset_environments(11);
    two.reset_environments(11);
    for (int iteration = 0; iteration < 4; ++iteration) {
      const PpoUpdateStatistics with_one = one.iterate();
      const PpoUpdateStatistics with_two = two.iterate();
      EXPECT_EQ(with_two.loss, with_one.loss);
      EXPECT_EQ(with_two.value_loss, with_one.value_loss);
      EXPECT_EQ(with_two.policy_gradient_loss, with_one.policy_gradient_loss);
      EXPECT_EQ(with_two.approx_kl, with_one.approx_kl);
      ASSERT_TRUE(torch::equal(two.policy().flat_parameters(), one.policy().flat_parameters()))
          << "iteration " << iteration;
    }
    EXPECT_GT((one.policy().flat_parameters() - initial).abs().max().item<double>(), 1e-3);
    EXPECT_TRUE(torch::equal(two.optimizer().exp_avg(), one.optimizer().exp_avg()));
    EXPECT_TRUE(torch::equal(two.optimizer().exp_avg_sq(), one.optimizer().exp_avg_sq()));
  }
}

// The trainer refuses a bad thread count, naming the key.
TEST(PpoUpdateThreads, ThePpoTrainerRefusesOtherThreadCounts) {
  for (const std::int64_t threads : {0, 3}) {
    testing::PointMassVectorEnv env(4);
    try {
      Ppo ppo(env, point_mass_config(Activation::kTanh, threads));
      ADD_FAILURE() << threads << " update threads were accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("ppo.update_threads"), std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace upkie_rl

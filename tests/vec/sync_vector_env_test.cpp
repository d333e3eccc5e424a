#include "vec/sync_vector_env.hpp"

#include <gtest/gtest.h>

#include <array>
#include <limits>

#include "envs/registry/env_factory.hpp"
#include "vec/counting_env.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl {
namespace {

using testing::CountingEnv;

std::vector<std::unique_ptr<Env>> counting_envs(std::vector<int> lengths, bool truncate = false) {
  std::vector<std::unique_ptr<Env>> envs;
  for (int length : lengths) envs.push_back(std::make_unique<CountingEnv>(length, truncate));
  return envs;
}

TEST(SyncVectorEnv, ResetSeedsEnvIWithSeedPlusI) {
  SyncVectorEnv venv(counting_envs({3, 3, 3}));
  const std::span<const float> observations = venv.reset(100);
  ASSERT_EQ(observations.size(), 9u);
  EXPECT_EQ(observations[0], 100.0f);
  EXPECT_EQ(observations[3], 101.0f);
  EXPECT_EQ(observations[6], 102.0f);
}

TEST(SyncVectorEnv, AutoResetKeepsTheFinalObservation) {
  SyncVectorEnv venv(counting_envs({2, 3}));
  venv.reset(0);
  const std::array<float, 2> actions{1.0f, 2.0f};
  const VectorStep& first = venv.step(actions);
  EXPECT_EQ(first.terminated[0], 0);
  EXPECT_EQ(first.rewards[1], 2.0f);
  const VectorStep& second = venv.step(actions);
  // Env 0 ended at its second step: final observation kept, new episode returned.
  EXPECT_EQ(second.terminated[0], 1);
  EXPECT_EQ(second.truncated[0], 0);
  EXPECT_EQ(second.final_observations[0], 0.0f);  // seed of the ended episode
  EXPECT_EQ(second.final_observations[1], 2.0f);  // its step count
  EXPECT_EQ(second.final_observations[2], 1.0f);  // its last action
  EXPECT_EQ(second.observations[0], 1000.0f);     // unseeded reset: the generator goes on
  EXPECT_EQ(second.observations[1], 0.0f);
  EXPECT_EQ(second.episode_returns[0], 2.0);
  EXPECT_EQ(second.episode_lengths[0], 2);
  EXPECT_EQ(second.terminated[1], 0);
  EXPECT_EQ(second.observations[4], 2.0f);
  const VectorStep& third = venv.step(actions);
  EXPECT_EQ(third.terminated[0], 0);
  EXPECT_EQ(third.episode_lengths[0], 0);
  EXPECT_EQ(third.terminated[1], 1);
  EXPECT_EQ(third.episode_returns[1], 6.0);
  EXPECT_EQ(third.episode_lengths[1], 3);
}

TEST(SyncVectorEnv, NextStepAutoresetResetsOnTheFollowingStep) {
  SyncVectorEnv venv(counting_envs({2, 3}), AutoresetMode::kNextStep);
  venv.reset(0);
  const std::array<float, 2> actions{1.0f, 2.0f};
  venv.step(actions);
  const VectorStep& second = venv.step(actions);
  // Env 0 ended: its last observation is returned (and kept as final), no reset yet.
  EXPECT_EQ(second.terminated[0], 1);
  EXPECT_EQ(second.observations[0], 0.0f);
  EXPECT_EQ(second.observations[1], 2.0f);
  EXPECT_EQ(second.final_observations[1], 2.0f);
  EXPECT_EQ(second.episode_returns[0], 2.0);
  EXPECT_EQ(second.episode_lengths[0], 2);
  const VectorStep& third = venv.step(actions);
  // The following step resets env 0 instead of stepping it: reward 0, flags false.
  EXPECT_EQ(third.observations[0], 1000.0f);  // unseeded reset: the generator goes on
  EXPECT_EQ(third.observations[1], 0.0f);
  EXPECT_EQ(third.rewards[0], 0.0f);
  EXPECT_EQ(third.terminated[0], 0);
  EXPECT_EQ(third.truncated[0], 0);
  EXPECT_EQ(third.episode_lengths[0], 0);
  // Env 1 runs on as in the same-step mode and ends at its third step.
  EXPECT_EQ(third.terminated[1], 1);
  EXPECT_EQ(third.episode_returns[1], 6.0);
  const VectorStep& fourth = venv.step(actions);
  EXPECT_EQ(fourth.observations[1], 1.0f);  // env 0's new episode, first step
  EXPECT_EQ(fourth.rewards[1], 0.0f);       // env 1 is being reset
  EXPECT_EQ(fourth.observations[3], 1001.0f);
}

TEST(SyncVectorEnv, UnseededResetLetsGeneratorsContinue) {
  SyncVectorEnv venv(counting_envs({3, 3}));
  venv.reset(5);
  const std::span<const float> observations = venv.reset(std::nullopt);
  EXPECT_EQ(observations[0], 1005.0f);
  EXPECT_EQ(observations[3], 1006.0f);
}

TEST(SyncVectorEnv, TruncationIsReportedApart) {
  SyncVectorEnv venv(counting_envs({1}, /*truncate=*/true));
  venv.reset(0);
  const std::array<float, 1> action{0.5f};
  const VectorStep& step = venv.step(action);
  EXPECT_EQ(step.truncated[0], 1);
  EXPECT_EQ(step.terminated[0], 0);
  EXPECT_EQ(step.final_observations[1], 1.0f);
}

TEST(SyncVectorEnv, BadInput) {
  SyncVectorEnv venv(counting_envs({3, 3}));
  const std::array<float, 2> actions{0.0f, 0.0f};
  EXPECT_THROW(venv.step(actions), std::logic_error);  // before reset
  venv.reset(0);
  const std::array<float, 3> wrong_size{};
  EXPECT_THROW(venv.step(wrong_size), std::invalid_argument);
  const std::array<float, 2> nan{0.0f, std::numeric_limits<float>::quiet_NaN()};
  EXPECT_THROW(venv.step(nan), std::invalid_argument);
  EXPECT_THROW(SyncVectorEnv(std::vector<std::unique_ptr<Env>>{}), std::invalid_argument);
}

TEST(MakeVectorEnv, SyncOrThreadPool) {
  auto sync = make_vector_env("Upkie-Mock-Pendulum", {}, 3, 0);
  EXPECT_EQ(sync->num_envs(), 3u);
  EXPECT_EQ(sync->observation_space().size(), 4u);
  EXPECT_NE(dynamic_cast<SyncVectorEnv*>(sync.get()), nullptr);
  auto pooled = make_vector_env("Upkie-Mock-Pendulum", {}, 3, 8);  // capped at 3 workers
  EXPECT_EQ(pooled->num_envs(), 3u);
  EXPECT_EQ(dynamic_cast<SyncVectorEnv*>(pooled.get()), nullptr);
  EXPECT_THROW(make_vector_env("Upkie-Mock-Pendulum", {}, 0, 0), std::invalid_argument);
  EXPECT_THROW(make_vector_env("Upkie-Mock-Pendulum", {{"nope", "1"}}, 2, 0),
               std::invalid_argument);
}

TEST(MakeVectorEnv, EnvIMatchesASingleEnvSeededWithSeedPlusI) {
  const EnvOptions options = {{"init_rand_pitch", "0.1"}, {"init_rand_v_x", "0.2"}};
  auto venv = make_vector_env("Upkie-Bullet-Pendulum", options, 3, 0);
  const std::span<const float> observations = venv->reset(10);
  auto single = make_env("Upkie-Bullet-Pendulum", options);
  std::array<float, 4> observation{};
  single->reset(12, observation);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(observations[2 * 4 + j], observation[j]);
  EXPECT_NE(observations[0], observations[4]);  // different seeds, different pitches
}

}  // namespace
}  // namespace upkie_rl

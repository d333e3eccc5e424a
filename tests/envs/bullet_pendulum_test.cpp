/// Behaviours of the environments on the Bullet backend (physics, so slower tests).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "envs/kinds/pendulum_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/wrappers/time_limit.hpp"

namespace upkie_rl {
namespace {

struct Episode {
  int length = 0;
  double total_reward = 0.0;
  bool terminated = false;
  bool truncated = false;
  std::vector<float> observations;
};

/// Runs one episode of the pendulum with ground velocity = gains · observation.
Episode run_linear(Env& env, const std::array<float, 4>& gains, std::uint64_t seed) {
  Episode episode;
  std::array<float, 4> observation{};
  env.reset(seed, observation);
  while (!episode.terminated && !episode.truncated && episode.length < 1000) {
    float velocity = 0.0f;
    for (std::size_t i = 0; i < 4; ++i) velocity += gains[i] * observation[i];
    const std::array<float, 1> action{velocity};
    const StepResult result = env.step(action, observation);
    episode.observations.insert(episode.observations.end(), observation.begin(), observation.end());
    episode.total_reward += result.reward;
    episode.terminated = result.terminated;
    episode.truncated = result.truncated;
    ++episode.length;
  }
  return episode;
}

TEST(BulletPendulum, LinearControllerLastsTheWholeEpisode) {
  auto env = make_env("Upkie-Bullet-Pendulum");
  const Episode episode = run_linear(*env, {10.0f, 1.0f, 0.0f, 0.1f}, 0);
  EXPECT_EQ(episode.length, 300);
  EXPECT_TRUE(episode.truncated);
  EXPECT_FALSE(episode.terminated);
  // Balanced: the reward stays near its maximum of 1.
  EXPECT_GT(episode.total_reward, 250.0);
}

TEST(BulletPendulum, ZeroControllerFalls) {
  auto env = make_env("Upkie-Bullet-Pendulum");
  const Episode episode = run_linear(*env, {0.0f, 0.0f, 0.0f, 0.0f}, 0);
  EXPECT_TRUE(episode.terminated);
  EXPECT_LT(episode.length, 300);
  auto* limit = dynamic_cast<TimeLimit*>(env.get());
  ASSERT_NE(limit, nullptr);
  auto* pendulum = dynamic_cast<PendulumEnv*>(&limit->inner());
  ASSERT_NE(pendulum, nullptr);
  EXPECT_EQ(pendulum->termination_reason(), BalanceTermination::Reason::kFall);
}

TEST(BulletPendulum, SameSeedSameTrajectory) {
  const EnvOptions options = {{"init_rand_pitch", "0.05"}, {"init_rand_omega_y", "0.2"}};
  auto a = make_env("Upkie-Bullet-Pendulum", options);
  auto b = make_env("Upkie-Bullet-Pendulum", options);
  const std::array<float, 4> gains{10.0f, 1.0f, 0.0f, 0.1f};
  const Episode first = run_linear(*a, gains, 42);
  const Episode second = run_linear(*b, gains, 42);
  ASSERT_EQ(first.length, second.length);
  EXPECT_EQ(first.observations, second.observations);  // Bit-identical.
  EXPECT_EQ(first.total_reward, second.total_reward);
  // Another seed gives another trajectory, and re-seeding reproduces the first.
  const Episode other = run_linear(*a, gains, 43);
  EXPECT_NE(other.observations, first.observations);
  const Episode again = run_linear(*a, gains, 42);
  EXPECT_EQ(again.observations, first.observations);
}

TEST(BulletServos, NeutralActionGivesValidObservations) {
  auto env = make_env("Upkie-Bullet-Servos");
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  env->reset(0, observation);
  env->neutral_action(action);
  for (int step = 0; step < 50; ++step) env->step(action, observation);
  for (float value : observation) EXPECT_TRUE(std::isfinite(value));
  EXPECT_NEAR(env->full_observation()->time, 50 * 0.005, 1e-9);
}

TEST(BulletServosTask, ZeroActionRunsUntilTerminationOrTruncation) {
  auto env = make_env("Upkie-Bullet-ServosTask");
  std::vector<float> observation(12);
  const std::vector<float> action(6, 0.0f);
  env->reset(0, observation);
  StepResult result;
  int steps = 0;
  while (!result.terminated && !result.truncated) {
    result = env->step(action, observation);
    ++steps;
    ASSERT_LE(steps, 300);
    ASSERT_LE(result.reward, 1.0);
  }
  for (float value : observation) EXPECT_TRUE(std::isfinite(value));
}

}  // namespace
}  // namespace upkie_rl

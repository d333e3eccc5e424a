#include "vec/thread_pool_vector_env.hpp"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <random>
#include <string>

#include "vec/counting_env.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl {
namespace {

/// Steps `venv` with reproducible pseudo-random actions and concatenates everything it
/// returns.
struct Trace {
  std::vector<float> observations, rewards, final_observations;
  std::vector<std::uint8_t> terminated, truncated;
  std::vector<double> returns;
};

Trace run(VectorEnv& venv, int steps, std::uint64_t seed) {
  Trace trace;
  std::mt19937_64 generator(1234);
  const std::span<const float> first = venv.reset(seed);
  trace.observations.assign(first.begin(), first.end());
  std::vector<float> actions(venv.num_envs() * venv.action_space().size());
  for (int t = 0; t < steps; ++t) {
    for (float& a : actions) a = static_cast<float>(generator() % 2001) / 1000.0f - 1.0f;
    const VectorStep& step = venv.step(actions);
    trace.observations.insert(trace.observations.end(), step.observations.begin(),
                              step.observations.end());
    trace.rewards.insert(trace.rewards.end(), step.rewards.begin(), step.rewards.end());
    trace.terminated.insert(trace.terminated.end(), step.terminated.begin(), step.terminated.end());
    trace.truncated.insert(trace.truncated.end(), step.truncated.begin(), step.truncated.end());
    for (std::size_t i = 0; i < venv.num_envs(); ++i) {
      if (step.terminated[i] || step.truncated[i]) {
        const auto row = step.final_observations.begin() + i * venv.observation_space().size();
        trace.final_observations.insert(trace.final_observations.end(), row,
                                        row + venv.observation_space().size());
        trace.returns.push_back(step.episode_returns[i]);
      }
    }
  }
  return trace;
}

void expect_same(const Trace& a, const Trace& b) {
  EXPECT_EQ(a.observations, b.observations);
  EXPECT_EQ(a.rewards, b.rewards);
  EXPECT_EQ(a.terminated, b.terminated);
  EXPECT_EQ(a.truncated, b.truncated);
  EXPECT_EQ(a.final_observations, b.final_observations);
  EXPECT_EQ(a.returns, b.returns);
}

TEST(ThreadPoolVectorEnv, BitIdenticalToSynchronousOnBullet) {
  const EnvOptions options = {
      {"init_rand_pitch", "0.2"}, {"init_rand_omega_y", "0.5"}, {"max_episode_steps", "40"}};
  auto sync = make_vector_env("Upkie-Bullet-Pendulum", options, 5, 0);
  const Trace expected = run(*sync, 120, 7);
  ASSERT_FALSE(expected.returns.empty());  // episodes ended and auto-reset
  for (std::size_t threads : {1u, 2u, 3u}) {
    auto pooled = make_vector_env("Upkie-Bullet-Pendulum", options, 5, threads);
    SCOPED_TRACE(threads);
    expect_same(run(*pooled, 120, 7), expected);
  }
}

TEST(ThreadPoolVectorEnv, BitIdenticalToSynchronousWithNextStepAutoreset) {
  const EnvOptions options = {{"init_rand_pitch", "0.2"}, {"max_episode_steps", "30"}};
  auto sync = make_vector_env("Upkie-Bullet-Pendulum", options, 4, 0, AutoresetMode::kNextStep);
  auto pooled = make_vector_env("Upkie-Bullet-Pendulum", options, 4, 2, AutoresetMode::kNextStep);
  const Trace expected = run(*sync, 80, 5);
  ASSERT_FALSE(expected.returns.empty());
  expect_same(run(*pooled, 80, 5), expected);
}

TEST(ThreadPoolVectorEnv, BitIdenticalToSynchronousOnServosTask) {
  auto sync = make_vector_env("Upkie-Bullet-ServosTask", {{"max_episode_steps", "25"}}, 4, 0);
  auto pooled = make_vector_env("Upkie-Bullet-ServosTask", {{"max_episode_steps", "25"}}, 4, 2);
  expect_same(run(*pooled, 60, 3), run(*sync, 60, 3));
}

TEST(ThreadPoolVectorEnv, EnvErrorsAreRethrownAndThePoolStaysUsable) {
  std::vector<std::unique_ptr<Env>> envs;
  for (int i = 0; i < 4; ++i) envs.push_back(std::make_unique<testing::CountingEnv>(3));
  ThreadPoolVectorEnv venv(std::move(envs), 2);
  venv.reset(0);
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  // Envs 0 and 3 fail: the error of the lowest index (0, NaN) is re-thrown, whichever
  // worker stepped which, and the other environments were stepped all the same.
  for (int attempt = 0; attempt < 20; ++attempt) {
    std::array<float, 4> actions{kNaN, 0.5f, 0.5f, kInfinity};
    try {
      venv.step(actions);
      FAIL() << "no error";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("is NaN"), std::string::npos) << error.what();
    }
  }
  std::array<float, 4> actions{0.0f, 0.0f, 0.0f, 1.0f};
  const VectorStep& step = venv.step(actions);
  EXPECT_EQ(step.rewards[3], 1.0f);
  // Env 1 has taken 21 steps (episodes of 3): the 21st ended an episode and auto-reset.
  // Env 0 refused its 20 NaN actions and has taken 1 step.
  const std::size_t observation_size = venv.observation_space().size();
  EXPECT_EQ(step.terminated[1], 1);
  EXPECT_EQ(step.episode_lengths[1], 3);
  EXPECT_EQ(step.observations[observation_size + 1], 0.0f);
  EXPECT_EQ(step.observations[1], 1.0f);
}

TEST(ThreadPoolVectorEnv, RefusesBadThreadCounts) {
  auto make = [](std::size_t threads) {
    std::vector<std::unique_ptr<Env>> envs;
    envs.push_back(std::make_unique<testing::CountingEnv>());
    envs.push_back(std::make_unique<testing::CountingEnv>());
    return ThreadPoolVectorEnv(std::move(envs), threads);
  };
  EXPECT_THROW(make(0), std::invalid_argument);
  EXPECT_THROW(make(3), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl

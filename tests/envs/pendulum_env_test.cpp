#include "envs/kinds/pendulum_env.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "envs/registry/env_factory.hpp"
#include "envs/scripted_simulation.hpp"
#include "envs/wrappers/time_limit.hpp"
#include "sim/mock_simulation.hpp"

namespace upkie_rl {
namespace {

using testing::pendulum_state;

// As the seed defines them, except p_dot: measured, it overshoots a_max, so it is unbounded.
TEST(PendulumEnv, SpacesAsTheSeedDefines) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  const BoxSpace& observation = env->observation_space();
  EXPECT_EQ(observation.names, (std::vector<std::string>{"theta", "p", "theta_dot", "p_dot"}));
  EXPECT_FLOAT_EQ(observation.high[0], static_cast<float>(M_PI));
  EXPECT_TRUE(std::isinf(observation.high[1]));
  EXPECT_FLOAT_EQ(observation.high[2], 1000.0f);
  EXPECT_TRUE(std::isinf(observation.high[3]));
  ASSERT_EQ(env->action_space().size(), 1u);
  EXPECT_FLOAT_EQ(env->action_space().low[0], -1.0f);
  EXPECT_FLOAT_EQ(env->action_space().high[0], 1.0f);
}

TEST(PendulumEnv, ObservationFromTheFullObservation) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  simulation->on_reset = pendulum_state(0.1, 0.2, 0.3, 0.4);
  std::array<float, 4> observation{};
  env->reset(0, observation);
  EXPECT_FLOAT_EQ(observation[0], 0.1f);
  EXPECT_FLOAT_EQ(observation[1], 0.2f);
  EXPECT_FLOAT_EQ(observation[2], 0.3f);
  EXPECT_FLOAT_EQ(observation[3], 0.4f);
}

TEST(PendulumEnv, RewardIsSeedEquationNineWithZeroHistoryAtReset) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  simulation->script = {pendulum_state(0.1, 0.0, 0.2, 0.3), pendulum_state(0.0, 0.0, 0.0, 0.0)};
  std::array<float, 4> observation{};
  env->reset(0, observation);
  const std::array<float, 1> first{0.5f};
  EXPECT_NEAR(env->step(first, observation).reward, -0.21, 1e-7);
  const std::array<float, 1> second{0.3f};
  // Δa = -0.2, Δ²a = -0.7 (float 0.3 and 0.5 are exact enough for 1e-6).
  EXPECT_NEAR(env->step(second, observation).reward, 0.095, 1e-6);
  env->reset(std::nullopt, observation);
  simulation->script = {pendulum_state(0.1, 0.0, 0.2, 0.3)};
  EXPECT_NEAR(env->step(first, observation).reward, -0.21, 1e-7);
}

TEST(PendulumEnv, TerminationsInTheSeedOrderRelativeToTheResetPosition) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  std::array<float, 4> observation{};
  const std::array<float, 1> action{0.0f};
  using Reason = BalanceTermination::Reason;
  // p0 = 10: p = 14.9 is a drift of 4.9, not terminal.
  simulation->on_reset = pendulum_state(0.0, 10.0, 0.0, 0.0);
  env->reset(0, observation);
  simulation->script = {pendulum_state(0.0, 14.9, 0.0, 0.0)};
  EXPECT_FALSE(env->step(action, observation).terminated);
  simulation->script = {pendulum_state(0.0, 15.1, 0.0, 0.0)};
  EXPECT_TRUE(env->step(action, observation).terminated);
  EXPECT_EQ(env->termination_reason(), Reason::kPositionDrift);
  // Every condition at once: the fall is reported.
  env->reset(0, observation);
  simulation->script = {pendulum_state(1.5, 20.0, 20.0, 3.0)};
  EXPECT_TRUE(env->step(action, observation).terminated);
  EXPECT_EQ(env->termination_reason(), Reason::kFall);
  env->reset(0, observation);
  simulation->script = {pendulum_state(0.0, 10.0, -10.5, 3.0)};
  EXPECT_TRUE(env->step(action, observation).terminated);
  EXPECT_EQ(env->termination_reason(), Reason::kAngularVelocity);
  env->reset(0, observation);
  simulation->script = {pendulum_state(0.0, 10.0, 0.0, 2.5)};
  const StepResult result = env->step(action, observation);
  EXPECT_TRUE(result.terminated);
  EXPECT_FALSE(result.truncated);
  EXPECT_EQ(env->termination_reason(), Reason::kLinearVelocity);
}

TEST(PendulumEnv, HugeActionIsClampedToTheGroundVelocityBound) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  std::array<float, 4> observation{};
  env->reset(0, observation);
  const std::array<float, 1> huge{1111.1f};
  env->step(huge, observation);
  const ServoAction& sent = simulation->received.back();
  const double r = 0.05;
  EXPECT_NEAR(sent[kLeftWheel].velocity * r, 1.0, 1e-9);
  EXPECT_NEAR(sent[kRightWheel].velocity * r, -1.0, 1e-9);
  EXPECT_TRUE(std::isnan(sent[kLeftWheel].position));
  EXPECT_DOUBLE_EQ(sent[kLeftWheel].maximum_torque, 1.7);
  const std::array<float, 1> nan{std::numeric_limits<float>::quiet_NaN()};
  EXPECT_THROW(env->step(nan, observation), std::invalid_argument);
  const std::array<float, 2> too_long{0.0f, 0.0f};
  EXPECT_THROW(env->step(too_long, observation), std::invalid_argument);
}

TEST(PendulumEnv, LegsStartAtTheMeasuredAnglesAndDecayTowardZero) {
  auto [simulation, env] = testing::make_scripted_env<PendulumEnv>();
  simulation->on_reset.servo[kLeftKnee].position = 0.5;
  simulation->on_reset.servo[kRightHip].position = -0.2;
  std::array<float, 4> observation{};
  env->reset(0, observation);
  const std::array<float, 1> action{0.0f};
  env->step(action, observation);
  env->step(action, observation);
  const double decay = 1.0 - 0.005 / 1.0;
  EXPECT_NEAR(simulation->received[0][kLeftKnee].position, 0.5 * decay, 1e-12);
  EXPECT_NEAR(simulation->received[1][kLeftKnee].position, 0.5 * decay * decay, 1e-12);
  EXPECT_NEAR(simulation->received[1][kRightHip].position, -0.2 * decay * decay, 1e-12);
  EXPECT_DOUBLE_EQ(simulation->received[1][kLeftHip].position, 0.0);
  EXPECT_DOUBLE_EQ(simulation->received[0][kLeftKnee].maximum_torque, 16.0);
  EXPECT_DOUBLE_EQ(simulation->received[0][kLeftKnee].velocity, 0.0);
}

TEST(PendulumEnv, RegistryTruncatesAt300Steps) {
  auto env = make_env("Upkie-Mock-Pendulum");
  std::array<float, 4> observation{};
  env->reset(0, observation);
  const std::array<float, 1> action{0.0f};
  for (int step = 1; step < 300; ++step) {
    const StepResult result = env->step(action, observation);
    ASSERT_FALSE(result.truncated) << "step " << step;
    ASSERT_FALSE(result.terminated) << "step " << step;
    EXPECT_DOUBLE_EQ(result.reward, 1.0);  // Mock: upright, at rest.
  }
  EXPECT_TRUE(env->step(action, observation).truncated);
  env->reset(std::nullopt, observation);
  EXPECT_FALSE(env->step(action, observation).truncated);
}

TEST(PendulumEnv, OptionsChangeTheTask) {
  auto env =
      make_env("Upkie-Mock-Pendulum",
               {{"max_ground_velocity", "2.5"}, {"max_episode_steps", "3"}, {"frequency", "100"}});
  EXPECT_FLOAT_EQ(env->action_space().high[0], 2.5f);
  EXPECT_DOUBLE_EQ(env->timestep(), 0.01);
  std::array<float, 4> observation{};
  env->reset(0, observation);
  const std::array<float, 1> action{0.0f};
  env->step(action, observation);
  env->step(action, observation);
  EXPECT_TRUE(env->step(action, observation).truncated);
}

}  // namespace
}  // namespace upkie_rl

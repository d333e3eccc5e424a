#include "envs/kinds/servos_task_env.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "envs/registry/env_factory.hpp"
#include "envs/scripted_simulation.hpp"

namespace upkie_rl {
namespace {

using testing::pendulum_state;

TEST(ServosTaskEnv, Spaces) {
  auto [simulation, env] = testing::make_scripted_env<ServosTaskEnv>();
  ASSERT_EQ(env->action_space().size(), 6u);
  ASSERT_EQ(env->observation_space().size(), 12u);
  EXPECT_EQ(env->action_space().names[2], "left_wheel");
  EXPECT_EQ(env->observation_space().names[0], "left_hip.position");
  EXPECT_EQ(env->observation_space().names[11], "right_wheel.velocity");
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(env->action_space().low[i], -1.0f);
    EXPECT_EQ(env->action_space().high[i], 1.0f);
  }
}

TEST(ServosTaskEnv, ActionMappingAsTheSeedDefines) {
  auto [simulation, env] = testing::make_scripted_env<ServosTaskEnv>();
  std::array<float, 12> observation{};
  env->reset(0, observation);
  // left_hip -1 -> lower, left_knee 1 -> upper, left_wheel 0.5 -> half the velocity limit,
  // right_hip 0 -> middle, right_knee 5 -> clamped to 1, right_wheel -1.
  const std::array<float, 6> action{-1.0f, 1.0f, 0.5f, 0.0f, 5.0f, -1.0f};
  env->step(action, observation);
  const ServoAction& sent = simulation->received.back();
  EXPECT_NEAR(sent[kLeftHip].position, -1.26, 1e-12);
  EXPECT_NEAR(sent[kLeftKnee].position, 2.51, 1e-12);
  EXPECT_NEAR(sent[kRightHip].position, 0.0, 1e-12);
  EXPECT_NEAR(sent[kRightKnee].position, 2.51, 1e-12);
  EXPECT_NEAR(sent[kLeftWheel].velocity, 0.5 * 111.0, 1e-9);
  EXPECT_NEAR(sent[kRightWheel].velocity, -111.0, 1e-9);
  EXPECT_TRUE(std::isnan(sent[kLeftWheel].position));
  EXPECT_DOUBLE_EQ(sent[kLeftWheel].kp_scale, 0.0);
  EXPECT_DOUBLE_EQ(sent[kLeftWheel].kd_scale, 1.7);
  EXPECT_DOUBLE_EQ(sent[kLeftHip].kp_scale, 2.0);
  EXPECT_DOUBLE_EQ(sent[kLeftHip].kd_scale, 1.7);
  EXPECT_DOUBLE_EQ(sent[kLeftHip].velocity, 0.0);
}

TEST(ServosTaskEnv, RewardOnTheActionMagnitude) {
  auto [simulation, env] = testing::make_scripted_env<ServosTaskEnv>();
  std::array<float, 12> observation{};
  env->reset(0, observation);
  simulation->script = {pendulum_state(0.2, 0.0, 1.0, -0.5)};
  // Legs at the middle of their range (0 rad), wheels at 0.01 of 111 rad/s each:
  // |a| = 2 · 1.11 = 2.22, Δ|a| = Δ²|a| = 2.22 at the first step.
  const std::array<float, 6> action{0.0f, 0.0f, 0.01f, 0.0f, 0.0f, -0.01f};
  const double magnitude = 2.0 * 0.01f * 111.0;
  const double expected =
      1.0 - (0.5 * 0.04 + 0.1 * 1.0 + 0.1 * 0.25 + (0.05 + 0.01 + 0.005) * magnitude * magnitude);
  const StepResult result = env->step(action, observation);
  EXPECT_NEAR(result.reward, expected, 1e-9);
  EXPECT_FALSE(result.terminated);
  simulation->script = {pendulum_state(1.2, 0.0, 0.0, 0.0)};
  EXPECT_TRUE(env->step(action, observation).terminated);
  EXPECT_EQ(env->termination_reason(), BalanceTermination::Reason::kFall);
}

TEST(ServosTaskEnv, ObservationIsPositionsAndVelocities) {
  auto [simulation, env] = testing::make_scripted_env<ServosTaskEnv>();
  simulation->on_reset.servo[kRightKnee].position = 0.7;
  simulation->on_reset.servo[kRightKnee].velocity = -0.3;
  std::array<float, 12> observation{};
  env->reset(0, observation);
  EXPECT_FLOAT_EQ(observation[2 * kRightKnee], 0.7f);
  EXPECT_FLOAT_EQ(observation[2 * kRightKnee + 1], -0.3f);
}

TEST(ServosTaskEnv, RegisteredWithA300StepLimit) {
  auto env = make_env("Upkie-Mock-ServosTask");
  std::array<float, 12> observation{};
  env->reset(0, observation);
  const std::array<float, 6> action{};
  int steps = 0;
  StepResult result;
  do {
    result = env->step(action, observation);
    ++steps;
  } while (!result.truncated && !result.terminated && steps < 1000);
  EXPECT_EQ(steps, 300);
  EXPECT_TRUE(result.truncated);
}

}  // namespace
}  // namespace upkie_rl

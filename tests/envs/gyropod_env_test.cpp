#include "envs/kinds/gyropod_env.hpp"

#include <gtest/gtest.h>

#include <array>

#include "envs/scripted_simulation.hpp"

namespace upkie_rl {
namespace {

TEST(GyropodEnv, Spaces) {
  auto [simulation, env] = testing::make_scripted_env<GyropodEnv>();
  EXPECT_EQ(env->observation_space().names,
            (std::vector<std::string>{"p", "theta", "psi", "p_dot", "theta_dot", "psi_dot"}));
  EXPECT_EQ(env->action_space().names,
            (std::vector<std::string>{"ground_velocity", "yaw_velocity"}));
  EXPECT_FLOAT_EQ(env->action_space().high[0], 3.0f);
  EXPECT_FLOAT_EQ(env->action_space().high[1], 1.0f);
}

TEST(GyropodEnv, PureYawGivesEqualWheelVelocities) {
  auto [simulation, env] = testing::make_scripted_env<GyropodEnv>();
  std::array<float, 6> observation{};
  env->reset(0, observation);
  const std::array<float, 2> yaw{0.0f, 0.5f};
  env->step(yaw, observation);
  const ServoAction& sent = simulation->received.back();
  EXPECT_NEAR(sent[kLeftWheel].velocity, sent[kRightWheel].velocity, 1e-12);
  EXPECT_NEAR(sent[kLeftWheel].velocity, 0.5 * 0.1524 / 0.05, 1e-9);  // k = 3.048
}

TEST(GyropodEnv, YawIntegratesTheCommandAndResets) {
  auto [simulation, env] = testing::make_scripted_env<GyropodEnv>();
  std::array<float, 6> observation{};
  env->reset(0, observation);
  const std::array<float, 2> yaw{0.0f, 0.5f};
  env->step(yaw, observation);
  EXPECT_FLOAT_EQ(observation[2], 0.5f * 0.005f);
  EXPECT_FLOAT_EQ(observation[5], 0.5f);
  env->reset(std::nullopt, observation);
  EXPECT_EQ(observation[2], 0.0f);
  EXPECT_EQ(observation[5], 0.0f);
}

TEST(GyropodEnv, TorqueLimitsAndFall) {
  auto [simulation, env] = testing::make_scripted_env<GyropodEnv>();
  std::array<float, 6> observation{};
  env->reset(0, observation);
  const std::array<float, 2> forward{1.0f, 0.0f};
  EXPECT_FALSE(env->step(forward, observation).terminated);
  const ServoAction& sent = simulation->received.back();
  for (std::size_t i = 0; i < kNumServos; ++i) {
    EXPECT_LT(sent[i].maximum_torque, is_wheel(i) ? 2.0 : 20.0);
  }
  EXPECT_NEAR(sent[kLeftWheel].velocity, 1.0 / 0.05, 1e-9);
  EXPECT_NEAR(sent[kRightWheel].velocity, -1.0 / 0.05, 1e-9);
  simulation->script = {testing::pendulum_state(-1.2, 0.0, 0.0, 0.0)};
  EXPECT_TRUE(env->step(forward, observation).terminated);
}

}  // namespace
}  // namespace upkie_rl

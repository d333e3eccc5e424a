#include "envs/tasks/velocity_command_limiter.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/tasks/velocity_task.hpp"

namespace upkie_rl {
namespace {

constexpr double kDt = 0.02;

TEST(VelocityCommandLimiter, RampsToTheTargetAtTheStatedRates) {
  VelocityCommandLimiter limiter(1.0, 3.0);
  const VelocityCommand target{0.5, -0.9};
  limiter.start(target);
  EXPECT_EQ(limiter.command(), (VelocityCommand{0.0, 0.0}));  // from rest
  // 0.5 m/s at 1 m/s²: 25 steps of 0.02 m/s; -0.9 rad/s at 3 rad/s²: 15 steps of 0.06.
  for (int step = 1; step <= 30; ++step) {
    const VelocityCommand& command = limiter.advance(target, kDt);
    EXPECT_NEAR(command.forward_velocity, std::min(0.02 * step, 0.5), 1e-12) << step;
    EXPECT_NEAR(command.yaw_rate, -std::min(0.06 * step, 0.9), 1e-12) << step;
  }
  EXPECT_EQ(limiter.command(), target);
  // A new target down the other way: the same rate, no overshoot.
  const VelocityCommand back{-0.5, 0.0};
  for (int step = 1; step <= 49; ++step) limiter.advance(back, kDt);
  EXPECT_NEAR(limiter.command().forward_velocity, 0.5 - 0.98, 1e-12);
  limiter.advance(back, kDt);
  limiter.advance(back, kDt);
  EXPECT_EQ(limiter.command(), back);
}

TEST(VelocityCommandLimiter, ZeroIsAStep) {
  VelocityCommandLimiter limiter(0.0, 0.0);
  limiter.start({0.7, 1.2});
  EXPECT_EQ(limiter.command(), (VelocityCommand{0.7, 1.2}));
  EXPECT_EQ(limiter.advance({-1.0, -1.5}, kDt), (VelocityCommand{-1.0, -1.5}));
  // One limited component, the other a step.
  VelocityCommandLimiter forward_only(2.0, 0.0);
  forward_only.start({1.0, 1.0});
  EXPECT_EQ(forward_only.command(), (VelocityCommand{0.0, 1.0}));
  EXPECT_NEAR(forward_only.advance({1.0, -1.0}, kDt).forward_velocity, 0.04, 1e-12);
  EXPECT_EQ(forward_only.command().yaw_rate, -1.0);
}

TEST(VelocityEnv, FollowedCommandRampsTowardTheTarget) {
  auto env = make_env("Upkie-Mock-Velocity",
                      {{"command_max_acceleration", "0.5"}, {"command_max_yaw_acceleration", "2"}});
  VelocityEnv* velocity = find_velocity_env(*env);
  ASSERT_NE(velocity, nullptr);
  velocity->set_command_override(VelocityCommand{0.3, 1.0});
  std::array<float, VelocityTask::kHeightObservationSize> observation{};
  env->reset(0, observation);
  EXPECT_EQ(velocity->target(), (VelocityCommand{0.3, 1.0}));
  EXPECT_EQ(velocity->command(), (VelocityCommand{0.0, 0.0}));
  EXPECT_FLOAT_EQ(observation[VelocityTask::kCommandIndex], 0.0f);
  const std::array<float, VelocityTask::kActionSize> action{};
  for (int step = 1; step <= 40; ++step) {
    env->step(action, observation);
    // The observation, the reward's command of the next step and the tracking: ramped.
    EXPECT_NEAR(observation[VelocityTask::kCommandIndex], std::min(0.01 * step, 0.3), 1e-6);
    EXPECT_NEAR(observation[VelocityTask::kCommandIndex + 1], std::min(0.04 * step, 1.0), 1e-6);
    EXPECT_NEAR(velocity->last_step_command().forward_velocity, std::min(0.01 * (step - 1), 0.3),
                1e-9);
    EXPECT_EQ(velocity->last_step_target(), (VelocityCommand{0.3, 1.0}));
  }
}

TEST(VelocityCommandLimiter, RateIsTheNextStepsChange) {
  VelocityCommandLimiter limiter(1.0, 0.0);  // the yaw rate steps
  limiter.start({0.05, 1.0});
  // Ramping: the forward limit; the step component none.
  EXPECT_DOUBLE_EQ(limiter.rate({0.05, 1.0}, kDt).forward_velocity, 1.0);
  EXPECT_EQ(limiter.rate({0.05, 1.0}, kDt).yaw_rate, 0.0);
  limiter.advance({0.05, 1.0}, kDt);
  limiter.advance({0.05, 1.0}, kDt);
  // The last step of the ramp: 0.01 m/s left, so 0.5 m/s² over it.
  EXPECT_NEAR(limiter.rate({0.05, 1.0}, kDt).forward_velocity, 0.5, 1e-9);
  limiter.advance({0.05, 1.0}, kDt);
  EXPECT_EQ(limiter.rate({0.05, 1.0}, kDt).forward_velocity, 0.0);          // at the target
  EXPECT_DOUBLE_EQ(limiter.rate({-1.0, 1.0}, kDt).forward_velocity, -1.0);  // a new one behind
}

TEST(VelocityEnv, ObservesTheCommandsAccelerationsWhenAsked) {
  auto plain = make_env("Upkie-Mock-Velocity", {});
  auto env = make_env("Upkie-Mock-Velocity", {{"observe_command_acceleration", "true"},
                                              {"command_max_acceleration", "0.5"},
                                              {"command_max_yaw_acceleration", "2"}});
  ASSERT_EQ(env->observation_space().size(), plain->observation_space().size() + 2);
  const std::size_t forward = plain->observation_space().size();
  EXPECT_EQ(env->observation_space().names[forward], "command.forward_acceleration");
  EXPECT_EQ(env->observation_space().names[forward + 1], "command.yaw_acceleration");
  VelocityEnv* velocity = find_velocity_env(*env);
  velocity->set_command_override(VelocityCommand{0.03, -1.0});
  std::vector<float> observation(env->observation_space().size());
  env->reset(0, observation);
  EXPECT_FLOAT_EQ(observation[forward], 0.5f);       // ramping up at the limit
  EXPECT_FLOAT_EQ(observation[forward + 1], -2.0f);  // and down in yaw
  const std::array<float, VelocityTask::kActionSize> action{};
  for (int step = 0; step < 5; ++step) env->step(action, observation);
  EXPECT_FLOAT_EQ(observation[forward], 0.0f);  // 0.03 m/s reached in 3 steps
  EXPECT_FLOAT_EQ(observation[forward + 1], -2.0f);
}

TEST(VelocityEnv, BadAccelerationLimitsNameTheOption) {
  for (const char* option : {"command_max_acceleration", "command_max_yaw_acceleration"}) {
    for (const char* value : {"-1", "nan", "inf"}) {
      std::string error;
      try {
        make_env("Upkie-Mock-Velocity", {{option, value}});
      } catch (const std::invalid_argument& caught) {
        error = caught.what();
      }
      EXPECT_NE(error.find(option), std::string::npos) << option << '=' << value << ": " << error;
    }
  }
  VelocityCommandRanges ranges;
  ranges.max_yaw_acceleration = -2.0;
  EXPECT_NE(ranges.problem().find("command_max_yaw_acceleration"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl

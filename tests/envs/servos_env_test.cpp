#include "envs/kinds/servos_env.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "envs/registry/env_factory.hpp"
#include "sim/mock_simulation.hpp"

namespace upkie_rl {
namespace {

std::unique_ptr<ServosEnv> make_mock_servos() {
  auto model = RobotModel::default_model();
  return std::make_unique<ServosEnv>(std::make_unique<MockSimulation>(model, 0.005), model);
}

TEST(ServosEnv, SpacesHaveSixJointsWithTheDocumentedKeys) {
  auto env = make_mock_servos();
  const DictSpace& actions = env->action_dict_space();
  const DictSpace& observations = env->observation_dict_space();
  ASSERT_EQ(actions.entries.size(), 6u);
  ASSERT_EQ(observations.entries.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(actions.entries[i].first, kServoNames[i]);
    EXPECT_EQ(actions.entries[i].second.names,
              (std::vector<std::string>{"position", "velocity", "feedforward_torque", "kp_scale",
                                        "kd_scale", "maximum_torque"}));
    EXPECT_EQ(
        observations.entries[i].second.names,
        (std::vector<std::string>{"position", "velocity", "torque", "temperature", "voltage"}));
  }
  EXPECT_EQ(env->action_space().size(), 36u);
  EXPECT_EQ(env->observation_space().size(), 30u);
  EXPECT_EQ(env->action_space().names[0], "left_hip.position");
  EXPECT_EQ(env->observation_space().names[29], "right_wheel.voltage");
  // Wheels are continuous, hips are limited.
  EXPECT_TRUE(std::isinf(env->action_space().low[2 * 6]));
  EXPECT_FLOAT_EQ(env->action_space().high[0], 1.26f);
}

TEST(ServosEnv, NeutralActionIsTheZeroController) {
  auto env = make_mock_servos();
  const ServoAction neutral = env->neutral_servo_action();
  for (std::size_t i = 0; i < kNumServos; ++i) {
    EXPECT_TRUE(std::isnan(neutral[i].position));
    EXPECT_EQ(neutral[i].velocity, 0.0);
    EXPECT_EQ(neutral[i].feedforward_torque, 0.0);
    EXPECT_EQ(neutral[i].kp_scale, 1.0);
    EXPECT_EQ(neutral[i].kd_scale, 1.0);
    EXPECT_EQ(neutral[i].maximum_torque, env->model().servo_limits(i).effort);
  }
  std::vector<float> flat(36);
  env->neutral_action(flat);
  EXPECT_TRUE(std::isnan(flat[0]));
  EXPECT_EQ(flat[3], 1.0f);
  EXPECT_FLOAT_EQ(flat[2 * 6 + 5], 1.7f);
}

TEST(ServosEnv, ExtremeActionsAreClampedNeverRaise) {
  auto env = make_mock_servos();
  env->reset_servos(0);
  ServoAction extreme{};
  for (ServoCommand& command : extreme) {
    command.position = 1000.0;
    command.velocity = -1000.0;
    command.feedforward_torque = 500.0;
    command.kp_scale = 100.0;
    command.kd_scale = -10.0;
    command.maximum_torque = 1000.0;
  }
  ServoAction clamped{};
  env->clamp_servo_action(extreme, clamped);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = env->model().servo_limits(i);
    if (limits.has_position_limits()) {
      EXPECT_EQ(clamped[i].position, limits.upper);
    } else {
      EXPECT_EQ(clamped[i].position, 1000.0);
    }
    EXPECT_EQ(clamped[i].velocity, -limits.velocity);
    EXPECT_EQ(clamped[i].feedforward_torque, limits.effort);
    EXPECT_EQ(clamped[i].kp_scale, ServosEnv::kMaxGainScale);
    EXPECT_EQ(clamped[i].kd_scale, 0.0);
    EXPECT_EQ(clamped[i].maximum_torque, limits.effort);
  }
  const Observation* observation = nullptr;
  ASSERT_NO_THROW(observation = &env->step_servos(extreme));
  for (const ServoObservation& servo : observation->servo) {
    EXPECT_TRUE(std::isfinite(servo.position));
    EXPECT_TRUE(std::isfinite(servo.velocity));
  }
}

TEST(ServosEnv, NanPositionPassesUnchanged) {
  auto env = make_mock_servos();
  ServoAction action = env->neutral_servo_action();
  ServoAction clamped{};
  env->clamp_servo_action(action, clamped);
  EXPECT_TRUE(std::isnan(clamped[kLeftHip].position));
}

TEST(ServosEnv, FlatStepRefusesBadActions) {
  auto env = make_mock_servos();
  std::vector<float> observation(30);
  env->reset(0, observation);
  std::vector<float> action(36);
  env->neutral_action(action);
  EXPECT_NO_THROW(env->step(action, observation));  // NaN positions are legal
  std::vector<float> short_action(35);
  EXPECT_THROW(env->step(short_action, observation), std::invalid_argument);
  action[1] = std::numeric_limits<float>::quiet_NaN();  // left_hip.velocity
  try {
    env->step(action, observation);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("left_hip.velocity"), std::string::npos);
  }
  env->neutral_action(action);
  action[6] = std::numeric_limits<float>::infinity();  // left_knee.position
  EXPECT_THROW(env->step(action, observation), std::invalid_argument);
}

TEST(ServosEnv, FlatObservationMatchesTheFullObservation) {
  auto env = make_mock_servos();
  std::vector<float> observation(30);
  env->reset(0, observation);
  std::vector<float> action(36);
  env->neutral_action(action);
  action[0] = 0.25f;         // left_hip.position
  action[6 * 2 + 1] = 3.0f;  // left_wheel.velocity
  const StepResult result = env->step(action, observation);
  EXPECT_EQ(result.reward, 0.0);
  EXPECT_FALSE(result.terminated);
  EXPECT_FALSE(result.truncated);
  EXPECT_FLOAT_EQ(observation[0], 0.25f);
  EXPECT_FLOAT_EQ(observation[2 * 5 + 1], 3.0f);
  EXPECT_FLOAT_EQ(observation[3], 42.0f);  // left_hip.temperature
  ASSERT_NE(env->full_observation(), nullptr);
  EXPECT_DOUBLE_EQ(env->full_observation()->servo[kLeftHip].position, 0.25);
}

TEST(ServosEnv, RegisteredAsFlatEnv) {
  auto env = make_env("Upkie-Mock-Servos");
  EXPECT_EQ(env->action_space().size(), 36u);
  EXPECT_EQ(env->observation_space().size(), 30u);
  EXPECT_DOUBLE_EQ(env->timestep(), 0.005);
}

}  // namespace
}  // namespace upkie_rl

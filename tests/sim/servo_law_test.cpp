#include "sim/servo_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace upkie_rl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(ServoLawTest, PositionAndVelocityTerms) {
  ServoCommand command;
  command.position = 0.5;
  command.velocity = 1.0;
  command.feedforward_torque = 0.1;
  command.kp_scale = 0.5;
  command.kd_scale = 2.0;
  // 0.1 + 20*0.5*(0.5-0.2) + 1*2*(1-0.25) = 0.1 + 3 + 1.5
  EXPECT_NEAR(servo_torque(command, 0.2, 0.25, ServoGains{}, 16.0), 4.6, 1e-12);
}

TEST(ServoLawTest, NaNPositionDropsPositionTerm) {
  ServoCommand command;
  command.position = kNaN;
  command.velocity = 2.0;
  EXPECT_NEAR(servo_torque(command, 100.0, 1.5, ServoGains{}, 1.7), 0.5, 1e-12);
}

TEST(ServoLawTest, ClampedByMaximumTorqueAndEffort) {
  ServoCommand command;
  command.velocity = 100.0;
  command.position = kNaN;
  EXPECT_DOUBLE_EQ(servo_torque(command, 0.0, 0.0, ServoGains{}, 1.7), 1.7);
  command.maximum_torque = 0.3;
  EXPECT_DOUBLE_EQ(servo_torque(command, 0.0, 0.0, ServoGains{}, 1.7), 0.3);
  command.velocity = -100.0;
  EXPECT_DOUBLE_EQ(servo_torque(command, 0.0, 0.0, ServoGains{}, 1.7), -0.3);
  command.maximum_torque = -5.0;  // a negative clamp is no torque, not a sign flip
  EXPECT_DOUBLE_EQ(servo_torque(command, 0.0, 0.0, ServoGains{}, 1.7), 0.0);
}

TEST(ServoLawTest, FeedforwardOnlyWithZeroGainScales) {
  ServoCommand command;
  command.kp_scale = 0.0;
  command.kd_scale = 0.0;
  command.position = 1.0;
  command.feedforward_torque = 0.42;
  EXPECT_DOUBLE_EQ(servo_torque(command, -3.0, 7.0, ServoGains{}, 16.0), 0.42);
}

TEST(ValidateServoActionTest, RefusesNonFiniteValuesNamingJointAndField) {
  ServoAction action{};
  EXPECT_NO_THROW(validate_servo_action(action));  // NaN position is "no position loop"
  action[kRightKnee].velocity = kNaN;
  try {
    validate_servo_action(action);
    FAIL() << "expected InvalidCommandError";
  } catch (const InvalidCommandError& error) {
    EXPECT_NE(std::string(error.what()).find("right_knee"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("velocity"), std::string::npos);
  }
  action[kRightKnee].velocity = 0.0;
  action[kLeftHip].kp_scale = INFINITY;
  EXPECT_THROW(validate_servo_action(action), InvalidCommandError);
  action[kLeftHip].kp_scale = 1.0;
  action[kLeftWheel].feedforward_torque = -INFINITY;
  EXPECT_THROW(validate_servo_action(action), InvalidCommandError);
  action[kLeftWheel].feedforward_torque = 0.0;
  action[kLeftWheel].position = INFINITY;
  EXPECT_THROW(validate_servo_action(action), InvalidCommandError);
  action[kLeftWheel].position = kNaN;
  action[kLeftWheel].maximum_torque = kNaN;
  EXPECT_THROW(validate_servo_action(action), InvalidCommandError);
}

TEST(ValidateServoActionTest, TheRobotRefusesTheInfiniteMaximumTorqueASimulationTakes) {
  ServoAction action{};  // maximum_torque +inf ("no clamp"), position NaN
  EXPECT_NO_THROW(validate_servo_action(action));
  EXPECT_NO_THROW(validate_servo_action(action, ServoActionTarget::kSimulation));
  try {
    validate_servo_action(action, ServoActionTarget::kRobot);
    FAIL() << "expected InvalidCommandError";
  } catch (const InvalidCommandError& error) {
    EXPECT_NE(std::string(error.what()).find("left_hip"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("maximum_torque"), std::string::npos);
  }
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  EXPECT_NO_THROW(validate_servo_action(action, ServoActionTarget::kRobot));  // NaN position
}

}  // namespace
}  // namespace upkie_rl

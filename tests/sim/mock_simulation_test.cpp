#include "sim/mock_simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace upkie_rl {
namespace {

class MockSimulationTest : public ::testing::Test {
 protected:
  std::shared_ptr<const RobotModel> model_ = RobotModel::default_model();
  MockSimulation simulation_{model_, 0.005};
};

TEST_F(MockSimulationTest, ResetGivesPlausibleUprightObservation) {
  ResetState state;
  state.joint_configuration[kLeftKnee] = 0.3;
  const Observation& observation = simulation_.reset(state);
  EXPECT_EQ(observation.time, 0.0);
  EXPECT_EQ(observation.base_orientation.pitch, 0.0);
  EXPECT_TRUE(observation.floor_contact.contact);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftKnee].position, 0.3);
  for (const ServoObservation& servo : observation.servo) {
    EXPECT_DOUBLE_EQ(servo.temperature, 42.0);
    EXPECT_DOUBLE_EQ(servo.voltage, 18.0);
  }
  // Upright: the IMU's z axis (down) is the ARS z axis (down), its x axis (backward)
  // opposes the ARS x axis (forward).
  const Eigen::Matrix3d rotation = observation.imu.orientation.toRotationMatrix();
  EXPECT_NEAR(rotation(2, 2), 1.0, 1e-12);
  EXPECT_NEAR(rotation(0, 0), -1.0, 1e-12);
  EXPECT_NEAR(observation.imu.raw_linear_acceleration.z(), -9.81, 1e-12);
}

TEST_F(MockSimulationTest, EchoesCommandedPositionsAndVelocities) {
  simulation_.reset(ResetState{});
  ServoAction action{};
  action[kLeftHip].position = 0.2;
  action[kLeftHip].velocity = 0.5;
  action[kLeftWheel].velocity = 10.0;
  action[kRightWheel].velocity = -10.0;
  action[kRightKnee].feedforward_torque = 0.42;
  const Observation& observation = simulation_.step(action);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftHip].position, 0.2);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftHip].velocity, 0.5);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftWheel].velocity, 10.0);
  // NaN position: the velocity is integrated.
  EXPECT_NEAR(observation.servo[kLeftWheel].position, 10.0 * 0.005, 1e-12);
  EXPECT_DOUBLE_EQ(observation.servo[kRightKnee].torque, 0.42);
  // Left-wheeled: +10 left, -10 right rolls forward at r * 10.
  EXPECT_NEAR(observation.wheel_odometry.velocity, model_->wheel_radius() * 10.0, 1e-12);
  EXPECT_NEAR(observation.wheel_odometry.position, model_->wheel_radius() * 10.0 * 0.005, 1e-12);
  EXPECT_NEAR(observation.time, 0.005, 1e-15);
  // Physics is untouched: still upright.
  EXPECT_EQ(observation.base_orientation.pitch, 0.0);
}

TEST_F(MockSimulationTest, TorqueWithinLimits) {
  simulation_.reset(ResetState{});
  ServoAction action{};
  action[kLeftWheel].feedforward_torque = 100.0;
  action[kLeftHip].feedforward_torque = -5.0;
  action[kLeftHip].maximum_torque = 2.0;
  const Observation& observation = simulation_.step(action);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftWheel].torque, model_->servo_limits(kLeftWheel).effort);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftHip].torque, -2.0);
}

TEST_F(MockSimulationTest, RefusesNonFiniteVelocity) {
  simulation_.reset(ResetState{});
  ServoAction action{};
  action[kRightHip].velocity = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(simulation_.step(action), InvalidCommandError);
}

TEST(MockSimulation, RefusesBadConstruction) {
  EXPECT_THROW(MockSimulation(nullptr, 0.005), std::invalid_argument);
  EXPECT_THROW(MockSimulation(RobotModel::default_model(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl

#include "sim/mock_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/servo_law.hpp"

namespace upkie_rl {

namespace {

// Orientation of the IMU frame (x backward, y left, z down) in the attitude reference
// frame (x forward, y right, z down) when the base is upright: a half turn about z.
const Eigen::Quaterniond kUprightImuOrientation{0.0, 0.0, 0.0, 1.0};

constexpr double kGravity = 9.81;              // [m/s^2]
constexpr double kServoTemperature = 42.0;     // [deg C]
constexpr double kServoVoltage = 18.0;         // [V]
constexpr double kStandingBaseHeight = 0.557;  // Base origin above the floor [m].

}  // namespace

MockSimulation::MockSimulation(std::shared_ptr<const RobotModel> model, double agent_timestep)
    : model_(std::move(model)), agent_timestep_(agent_timestep) {
  if (!model_) throw std::invalid_argument("MockSimulation: the robot model is null");
  if (!(agent_timestep_ > 0.0) || !std::isfinite(agent_timestep_)) {
    throw std::invalid_argument("MockSimulation: agent timestep must be positive and finite, got " +
                                std::to_string(agent_timestep_));
  }
}

const Observation& MockSimulation::reset(const ResetState& state) {
  observation_ = Observation{};
  for (std::size_t i = 0; i < kNumServos; ++i) {
    ServoObservation& servo = observation_.servo[i];
    servo.position = state.joint_configuration[i];
    servo.temperature = kServoTemperature;
    servo.voltage = kServoVoltage;
  }
  observation_.imu.orientation = kUprightImuOrientation;
  // At rest the accelerometer measures the reaction to gravity: up in the world, -z in
  // the IMU frame (z down).
  observation_.imu.raw_linear_acceleration = Eigen::Vector3d(0.0, 0.0, -kGravity);
  observation_.floor_contact.contact = true;
  observation_.has_sim = true;
  observation_.sim_base.position = Eigen::Vector3d(0.0, 0.0, kStandingBaseHeight);
  return observation_;
}

const Observation& MockSimulation::step(const ServoAction& action) {
  validate_servo_action(action);
  const double dt = agent_timestep_;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const ServoCommand& command = action[i];
    ServoObservation& servo = observation_.servo[i];
    servo.position =
        std::isnan(command.position) ? servo.position + command.velocity * dt : command.position;
    servo.velocity = command.velocity;
    const double torque_limit = servo_torque_limit(command, model_->servo_limits(i).effort);
    servo.torque = std::clamp(command.feedforward_torque, -torque_limit, torque_limit);
  }
  // Left-wheeled: a positive left-wheel velocity rolls forward.
  const double r = model_->wheel_radius();
  WheelOdometryObservation& odometry = observation_.wheel_odometry;
  odometry.velocity =
      0.5 * r *
      (observation_.servo[kLeftWheel].velocity - observation_.servo[kRightWheel].velocity);
  odometry.position += odometry.velocity * dt;
  observation_.time += dt;
  return observation_;
}

}  // namespace upkie_rl

#include "envs/kinds/ground_velocity_commander.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace upkie_rl {

GroundVelocityCommander::GroundVelocityCommander(const RobotModel& model, double timestep,
                                                 const GroundVelocityCommanderConfig& config)
    : wheels_(model.wheel_geometry()),
      filter_gain_(std::min(1.0, timestep / config.leg_time_constant)) {
  if (!(wheels_.radius > 0.0)) {
    throw std::invalid_argument("GroundVelocityCommander: wheel radius must be positive");
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    ServoCommand& command = action_[i];
    command.velocity = 0.0;
    command.feedforward_torque = 0.0;
    if (is_wheel(i)) {
      command.position = std::numeric_limits<double>::quiet_NaN();
      command.kp_scale = 1.0;
      command.kd_scale = 1.0;
      command.maximum_torque = config.wheel_maximum_torque;
    } else {
      command.position = 0.0;
      command.kp_scale = config.leg_gain_scale;
      command.kd_scale = config.leg_gain_scale;
      command.maximum_torque = config.leg_maximum_torque;
    }
  }
}

void GroundVelocityCommander::reset(const Observation& observation) {
  for (std::size_t i = 0; i < kNumServos; ++i) {
    if (!is_wheel(i)) action_[i].position = observation.servo[i].position;
    action_[i].velocity = 0.0;
  }
}

const ServoAction& GroundVelocityCommander::command(double ground_velocity, double yaw_velocity) {
  for (std::size_t i = 0; i < kNumServos; ++i) {
    if (!is_wheel(i)) action_[i].position += filter_gain_ * (0.0 - action_[i].position);
  }
  // Public Upkie's gyropod convention: a positive yaw velocity command makes both wheel
  // joint velocities positive (left wheel forward, right one backward: clockwise seen from
  // above), the opposite sign of WheelGeometry's yaw rate.
  const WheelVelocities wheels = wheels_.velocities(ground_velocity, -yaw_velocity);
  action_[kLeftWheel].velocity = wheels.left;
  action_[kRightWheel].velocity = wheels.right;
  return action_;
}

}  // namespace upkie_rl

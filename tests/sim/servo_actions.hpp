#pragma once
/// @file
/// Servo actions the simulation tests drive the robot with.

#include "sim/servo_command.hpp"

namespace upkie_rl::testing {

/// Zero torque on every joint.
inline ServoAction limp_action() {
  ServoAction action{};
  for (auto& command : action) {
    command.kp_scale = 0.0;
    command.kd_scale = 0.0;
  }
  return action;
}

/// Legs held at 0, wheels rolling the base at ground velocity `ground_velocity` [m/s].
inline ServoAction pendulum_action(double ground_velocity, double wheel_radius) {
  ServoAction action{};
  for (std::size_t servo : {kLeftHip, kLeftKnee, kRightHip, kRightKnee}) {
    action[servo].position = 0.0;
    action[servo].velocity = 0.0;
  }
  action[kLeftWheel].velocity = ground_velocity / wheel_radius;
  action[kRightWheel].velocity = -ground_velocity / wheel_radius;
  return action;
}

}  // namespace upkie_rl::testing

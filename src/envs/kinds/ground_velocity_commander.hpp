#pragma once
/// @file
/// GroundVelocityCommander: turns a ground velocity and yaw rate into servo commands,
/// holding the legs (the wheeled inverted pendulum view of Upkie used by the pendulum and
/// gyropod environments).

#include "model/robot_model.hpp"
#include "sim/observation.hpp"
#include "sim/servo_command.hpp"

namespace upkie_rl {

/// Settings of the leg and wheel commands.
struct GroundVelocityCommanderConfig {
  double leg_gain_scale = 1.0;        ///< kp_scale and kd_scale of hips and knees.
  double leg_maximum_torque = 16.0;   ///< [N.m]
  double leg_time_constant = 1.0;     ///< Of the low-pass filter toward 0 [s].
  double wheel_maximum_torque = 1.7;  ///< [N.m]
};

/// Wheels: position NaN, ω_left = +v/r + k·ψ̇, ω_right = -v/r + k·ψ̇ with k = (track/2)/r,
/// gain scales 1. Legs: targets start at the measured angles at reset and are low-pass
/// filtered toward 0 every step: target <- target + (dt/T)·(0 - target); velocity 0.
class GroundVelocityCommander {
 public:
  GroundVelocityCommander(const RobotModel& model, double timestep,
                          const GroundVelocityCommanderConfig& config = {});

  /// Takes the measured leg angles as targets.
  void reset(const Observation& observation);

  /// Filters the leg targets one step and returns the commands for this step.
  /// @param ground_velocity ṗ* [m/s]. @param yaw_velocity ψ̇* [rad/s].
  const ServoAction& command(double ground_velocity, double yaw_velocity);

  /// The last commands.
  const ServoAction& action() const { return action_; }

 private:
  WheelGeometry wheels_;
  double filter_gain_;  // dt / T, at most 1
  ServoAction action_{};
};

}  // namespace upkie_rl

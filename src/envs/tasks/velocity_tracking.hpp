#pragma once
/// @file
/// VelocityTracking: how well a velocity task's command was followed over an episode.

#include <cmath>

#include "envs/kinds/velocity_env.hpp"

namespace upkie_rl {

/// Sums of squared errors between command and measured base velocity (and height, with a
/// height command: LegKinematics::base_height) over the steps where
/// the robot is up (steps that did not end in a termination): against the command the robot
/// followed (ramped within the acceleration limits, VelocityCommandLimiter) and against the
/// target it ramped toward (the random draw or the scripted row).
struct VelocityTracking {
  double squared_forward_error = 0.0;         ///< Against the followed command [m²/s²]
  double squared_yaw_error = 0.0;             ///< [rad²/s²]
  double squared_forward_target_error = 0.0;  ///< Against the target [m²/s²]
  double squared_yaw_target_error = 0.0;      ///< [rad²/s²]
  double squared_height_error = 0.0;          ///< Against the followed command [m²]
  double squared_height_target_error = 0.0;   ///< Against the target [m²]
  int steps = 0;
  /// Whether the steps were of a task with a height command (the height errors count).
  bool height_command = false;
  bool active = false;  ///< Whether a velocity task's step was offered (even a terminated one).

  /// Adds the step `env` just took, unless it `terminated`.
  void add(const VelocityEnv& env, bool terminated) {
    active = true;
    height_command = height_command || env.command_ranges().height_command;
    if (terminated) return;
    add(env.last_step_command(), env.last_step_target(), env.measured_velocity());
  }

  /// Adds one step's command (its own target: no ramp) and measured velocity.
  void add(const VelocityCommand& command, const BaseVelocity& velocity) {
    add(command, command, velocity);
  }

  /// Adds one step's followed command, its target and the measured velocity.
  void add(const VelocityCommand& command, const VelocityCommand& target,
           const BaseVelocity& velocity) {
    const auto square = [](double error) { return error * error; };
    squared_forward_error += square(command.forward_velocity - velocity.forward_velocity);
    squared_yaw_error += square(command.yaw_rate - velocity.yaw_rate);
    squared_forward_target_error += square(target.forward_velocity - velocity.forward_velocity);
    squared_yaw_target_error += square(target.yaw_rate - velocity.yaw_rate);
    squared_height_error += square(command.height - velocity.height);
    squared_height_target_error += square(target.height - velocity.height);
    ++steps;
    active = true;
  }

  VelocityTracking& operator+=(const VelocityTracking& other) {
    squared_forward_error += other.squared_forward_error;
    squared_yaw_error += other.squared_yaw_error;
    squared_forward_target_error += other.squared_forward_target_error;
    squared_yaw_target_error += other.squared_yaw_target_error;
    squared_height_error += other.squared_height_error;
    squared_height_target_error += other.squared_height_target_error;
    steps += other.steps;
    active = active || other.active;
    height_command = height_command || other.height_command;
    return *this;
  }

  /// RMS forward velocity error against the followed command [m/s] (NaN without steps).
  double rms_forward() const { return rms(squared_forward_error); }
  /// RMS yaw rate error against the followed command [rad/s] (NaN without steps).
  double rms_yaw() const { return rms(squared_yaw_error); }
  /// RMS forward velocity error against the target [m/s] (NaN without steps).
  double rms_forward_target() const { return rms(squared_forward_target_error); }
  /// RMS yaw rate error against the target [rad/s] (NaN without steps).
  double rms_yaw_target() const { return rms(squared_yaw_target_error); }
  /// RMS base height error against the followed command [m] (NaN without steps or
  /// without a height command).
  double rms_height() const { return height_command ? rms(squared_height_error) : std::nan(""); }
  /// RMS base height error against the target [m] (NaN as rms_height).
  double rms_height_target() const {
    return height_command ? rms(squared_height_target_error) : std::nan("");
  }

 private:
  double rms(double sum_of_squares) const {
    return steps > 0 ? std::sqrt(sum_of_squares / steps) : std::nan("");
  }
};

}  // namespace upkie_rl

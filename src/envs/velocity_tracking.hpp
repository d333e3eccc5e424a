#pragma once
/// @file
/// VelocityTracking: how well a velocity task's command was followed over an episode.

#include <cmath>

#include "envs/velocity_env.hpp"

namespace upkie_rl {

/// Sums of squared errors between command and measured base velocity over the steps where
/// the robot is up (steps that did not end in a termination).
struct VelocityTracking {
  double squared_forward_error = 0.0;  ///< [m²/s²]
  double squared_yaw_error = 0.0;      ///< [rad²/s²]
  int steps = 0;
  bool active = false;  ///< Whether a velocity task's step was offered (even a terminated one).

  /// Adds the step `env` just took, unless it `terminated`.
  void add(const VelocityEnv& env, bool terminated) {
    active = true;
    if (terminated) return;
    const VelocityCommand& command = env.last_step_command();
    const BaseVelocity velocity = env.measured_velocity();
    add(command, velocity);
  }

  /// Adds one step's command and measured velocity.
  void add(const VelocityCommand& command, const BaseVelocity& velocity) {
    const double forward_error = command.forward_velocity - velocity.forward_velocity;
    const double yaw_error = command.yaw_rate - velocity.yaw_rate;
    squared_forward_error += forward_error * forward_error;
    squared_yaw_error += yaw_error * yaw_error;
    ++steps;
    active = true;
  }

  VelocityTracking& operator+=(const VelocityTracking& other) {
    squared_forward_error += other.squared_forward_error;
    squared_yaw_error += other.squared_yaw_error;
    steps += other.steps;
    active = active || other.active;
    return *this;
  }

  /// RMS forward velocity error [m/s] (NaN without steps).
  double rms_forward() const {
    return steps > 0 ? std::sqrt(squared_forward_error / steps) : std::nan("");
  }
  /// RMS yaw rate error [rad/s] (NaN without steps).
  double rms_yaw() const { return steps > 0 ? std::sqrt(squared_yaw_error / steps) : std::nan(""); }
};

}  // namespace upkie_rl

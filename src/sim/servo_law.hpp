#pragma once
/// @file
/// The servo law of the moteus position mode as emulated in simulation.

#include <algorithm>
#include <cmath>

#include "sim/servo_command.hpp"

namespace upkie_rl {

/// Gains of the simulated servo law (simulation parameters, not the real servos').
struct ServoGains {
  double kp = 20.0;  ///< [N.m/rad]
  double kd = 1.0;   ///< [N.m.s/rad]
};

/// Whether `gain` can be a servo gain (kp or kd): finite and non-negative.
inline bool is_valid_servo_gain(double gain) { return std::isfinite(gain) && gain >= 0.0; }

/// The largest torque [N.m] the servo applies for `command` on a joint of effort `effort`:
/// min(max_torque, effort), never negative.
inline double servo_torque_limit(const ServoCommand& command, double effort) {
  return std::max(0.0, std::min(command.maximum_torque, effort));
}

/// Torque [N.m] the servo applies for `command` at joint angle `position` [rad] and
/// velocity `velocity` [rad/s]:
/// clamp(tau_ff + kp*kp_scale*(q* - q) + kd*kd_scale*(qdot* - qdot), +-min(max_torque, effort)),
/// the position term dropped when q* is NaN.
inline double servo_torque(const ServoCommand& command, double position, double velocity,
                           const ServoGains& gains, double effort) {
  double torque =
      command.feedforward_torque + gains.kd * command.kd_scale * (command.velocity - velocity);
  if (!std::isnan(command.position)) {
    torque += gains.kp * command.kp_scale * (command.position - position);
  }
  const double limit = servo_torque_limit(command, effort);
  return std::clamp(torque, -limit, limit);
}

}  // namespace upkie_rl

#pragma once
/// @file
/// VelocityCommandLimiter: the acceleration limits of the velocity task's commands, as a
/// teleoperation stack applies them between a joystick and the robot.

#include "envs/tasks/velocity_command.hpp"

namespace upkie_rl {

/// Moves the command the robot follows toward a target (a random draw, a scripted row, a
/// joystick's) at most at `max_acceleration` [m/s²] forward and `max_yaw_acceleration`
/// [rad/s²] in yaw and `max_height_velocity` [m/s] in height; a limit of 0 passes the target
/// through at once (a step). Why: a wheeled inverted pendulum cannot follow a step of its forward
/// velocity (it must first lean, which moves its wheels the wrong way), so a step command measures
/// the physics, not the controller. Allocation-free.
class VelocityCommandLimiter {
 public:
  /// Limits as VelocityCommandRanges::max_acceleration, max_yaw_acceleration and
  /// max_height_velocity [m/s] (checked there: finite, non-negative).
  VelocityCommandLimiter(double max_acceleration, double max_yaw_acceleration,
                         double max_height_velocity = 0.0)
      : max_acceleration_(max_acceleration),
        max_yaw_acceleration_(max_yaw_acceleration),
        max_height_velocity_(max_height_velocity) {}

  /// Starts an episode toward `target`: a limited component starts at rest (velocities 0,
  /// the base at `rest_height` [m], where a reset leaves it), an unlimited one at its target.
  void start(const VelocityCommand& target, double rest_height = kStandingBaseHeight);

  /// Advances `dt` [s] toward `target`; returns the command.
  const VelocityCommand& advance(const VelocityCommand& target, double dt);

  /// The rate of change [per s] that advance(target, dt) would give each component now:
  /// ±its limit while ramping, less on the last step of a ramp, 0 at the target or for an
  /// unlimited component (it steps). Why: a controller that sees only the followed command
  /// cannot tell that it ramps; the classical balancer feeds the ramp's acceleration
  /// forward, and a policy can only if it is observed.
  VelocityCommand rate(const VelocityCommand& target, double dt) const;

  /// The command the robot follows now.
  const VelocityCommand& command() const { return command_; }

 private:
  double max_acceleration_;
  double max_yaw_acceleration_;
  double max_height_velocity_;
  VelocityCommand command_;
};

}  // namespace upkie_rl

#pragma once
/// @file
/// VelocityCommandLimiter: the acceleration limits of the velocity task's commands, as a
/// teleoperation stack applies them between a joystick and the robot.

#include "envs/velocity_command.hpp"

namespace upkie_rl {

/// Moves the command the robot follows toward a target (a random draw, a scripted row, a
/// joystick's) at most at `max_acceleration` [m/s²] forward and `max_yaw_acceleration`
/// [rad/s²] in yaw; a limit of 0 passes the target through at once (a step). Why: a
/// wheeled inverted pendulum cannot follow a step of its forward velocity (it must first
/// lean, which moves its wheels the wrong way), so a step command measures the physics,
/// not the controller. Allocation-free.
class VelocityCommandLimiter {
 public:
  /// Limits as VelocityCommandRanges::max_acceleration and max_yaw_acceleration (checked
  /// there: finite, non-negative).
  VelocityCommandLimiter(double max_acceleration, double max_yaw_acceleration)
      : max_acceleration_(max_acceleration), max_yaw_acceleration_(max_yaw_acceleration) {}

  /// Starts an episode toward `target`: a limited component starts at 0 (the robot at
  /// rest), an unlimited one at its target.
  void start(const VelocityCommand& target);

  /// Advances `dt` [s] toward `target`; returns the command.
  const VelocityCommand& advance(const VelocityCommand& target, double dt);

  /// The command the robot follows now.
  const VelocityCommand& command() const { return command_; }

 private:
  double max_acceleration_;
  double max_yaw_acceleration_;
  VelocityCommand command_;
};

}  // namespace upkie_rl

#pragma once
/// @file
/// The limits the robot runner's supervisor enforces, each on by default.

namespace upkie_rl {

/// Defaults follow Upkie's own protections (fall pitch 1 rad, 100 ms spine timeout, 5 stop
/// cycles) and its servo configuration; every bound is an option of `upkie-rl-agent`.
struct SupervisorLimits {
  double max_pitch = 1.0;  ///< |pitch| beyond it stops [rad] (Upkie's fall_pitch).
  double max_roll = 0.5;   ///< |roll| beyond it stops [rad].
  /// A measured joint angle beyond the joint's limits by more than this stops [rad].
  double joint_position_margin = 0.1;
  /// A measured joint velocity beyond this fraction of the joint's velocity limit stops.
  double joint_velocity_factor = 1.2;
  /// Rate limit of velocity commands (the wheels'), change per second [rad/s^2].
  double max_velocity_command_rate = 2000.0;
  /// Rate limit of position commands (the legs'), change per second [rad/s]: 2 rev/s, the
  /// velocity limit Upkie configures on its leg servos (a lower one destabilises the
  /// servos-balance test policy, which moves its legs to balance).
  double max_position_command_rate = 4.0 * 3.14159265358979323846;
  /// Cap of every command's maximum_torque [N.m]; never above the joint's effort, the
  /// spine's own limit (0: the effort).
  double max_torque = 0.0;
  /// The spine is silent when a request stays unanswered this long [s].
  double spine_timeout = 0.1;
  /// Stop after this many missed deadlines in a row (a cycle longer than 1.5 periods).
  /// (20 cycles of a 200 Hz task: 100 ms, the spine's own timeout, at least 50 ms late.)
  int max_consecutive_deadline_misses = 20;
  /// Stop after any one cycle longer than this many periods (20: 100 ms at 200 Hz).
  double max_cycle_periods = 20.0;
  /// Cycles of stop commands (zero wheel velocity, legs held) sent before the Stop request.
  int nb_stop_cycles = 5;

  /// @throws AgentError naming the first bound that is not positive and finite.
  void validate() const;
};

}  // namespace upkie_rl

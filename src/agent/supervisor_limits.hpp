#pragma once
/// @file
/// The limits the robot runner's supervisor enforces, each on by default, each declared once
/// (name, range, help) in declare_options(): upkie-rl-agent's flags, their checks and
/// validate() all read that one declaration.

#include "base/option_table.hpp"

namespace upkie_rl {

/// Defaults follow Upkie's own protections (fall pitch 1 rad, 100 ms spine timeout, 5 stop
/// cycles) and its servo configuration. Every range is finite and narrow enough that the
/// limit still limits (a bound no measurement can pass would switch the protection off
/// unnoticed); the reason for each bound is beside its declaration.
struct SupervisorLimits {
  double max_pitch = 1.0;              ///< |pitch| beyond it stops [rad] (Upkie's fall_pitch).
  double max_roll = 0.5;               ///< |roll| beyond it stops [rad].
  double joint_position_margin = 0.1;  ///< Angle allowed past a joint's limits [rad].
  double joint_velocity_factor = 1.2;  ///< Fraction of a joint's velocity limit allowed.
  double max_velocity_command_rate = 2000.0;  ///< Wheels' command rate limit [rad/s^2].
  /// Legs' command rate limit [rad/s]: 2 rev/s, the velocity limit Upkie configures on its
  /// leg servos (a lower one destabilises the servos-balance test policy, which moves its
  /// legs to balance).
  double max_position_command_rate = 4.0 * 3.14159265358979323846;
  /// Cap of every command's maximum_torque [N.m]; never above the joint's effort, the
  /// spine's own limit (0: the effort).
  double max_torque = 0.0;
  double spine_timeout = 0.1;  ///< The spine is silent when unanswered this long [s].
  /// Stop after this many missed deadlines in a row (a cycle longer than 1.5 periods).
  /// (20 cycles of a 200 Hz task: 100 ms, the spine's own timeout, at least 50 ms late.)
  int max_consecutive_deadline_misses = 20;
  double max_cycle_periods = 20.0;  ///< Stop after one cycle longer than this many periods.
  /// Cycles of stop commands (zero wheel velocity, legs held) sent before the Stop request.
  int nb_stop_cycles = 5;

  /// Declares every limit as an option named as its upkie-rl-agent flag without the dashes
  /// ("max_pitch" for --max-pitch), with its range and help.
  void declare_options(OptionTable& table);

  /// @throws AgentError naming the first limit outside its range (or not finite).
  void validate() const;
};

}  // namespace upkie_rl

#pragma once
/// @file
/// The limits the robot runner's supervisor enforces, each on by default, and the range
/// each may be set in.

namespace upkie_rl {

/// The closed range a limit may be set in: finite, and narrow enough that the limit still
/// limits (a bound no measurement can pass would switch the protection off unnoticed).
struct LimitRange {
  double min;
  double max;
};

/// Defaults follow Upkie's own protections (fall pitch 1 rad, 100 ms spine timeout, 5 stop
/// cycles) and its servo configuration; every bound is an option of `upkie-rl-agent`, in
/// the range declared next to it (used by the options and by validate()).
struct SupervisorLimits {
  double max_pitch = 1.0;  ///< |pitch| beyond it stops [rad] (Upkie's fall_pitch).
  /// The measured pitch is an arcsine, within +-pi/2: a bound of pi/2 could never trip.
  static constexpr LimitRange kMaxPitchRange{0.01, 1.5};
  double max_roll = 0.5;  ///< |roll| beyond it stops [rad].
  /// Beyond about pi/2 the robot lies on its side; same bound as the pitch.
  static constexpr LimitRange kMaxRollRange{0.01, 1.5};
  /// A measured joint angle beyond the joint's limits by more than this stops [rad].
  double joint_position_margin = 0.1;
  /// 1 rad past the URDF limits (+-1.26 and +-2.51 rad on the legs) is past the mechanics.
  static constexpr LimitRange kJointPositionMarginRange{0.0, 1.0};
  /// A measured joint velocity beyond this fraction of the joint's velocity limit stops.
  double joint_velocity_factor = 1.2;
  /// Three times the servos' velocity limits is beyond what they can reach.
  static constexpr LimitRange kJointVelocityFactorRange{0.1, 3.0};
  /// Rate limit of velocity commands (the wheels'), change per second [rad/s^2].
  double max_velocity_command_rate = 2000.0;
  /// At the top, 500 rad/s per 5 ms cycle: more than the wheels' 111 rad/s limit, so a
  /// higher bound would mean the same (no rate limit).
  static constexpr LimitRange kVelocityCommandRateRange{1.0, 1e5};
  /// Rate limit of position commands (the legs'), change per second [rad/s]: 2 rev/s, the
  /// velocity limit Upkie configures on its leg servos (a lower one destabilises the
  /// servos-balance test policy, which moves its legs to balance).
  double max_position_command_rate = 4.0 * 3.14159265358979323846;
  /// At the top, 5 rad per 5 ms cycle: more than a leg joint's whole range.
  static constexpr LimitRange kPositionCommandRateRange{0.1, 1000.0};
  /// Cap of every command's maximum_torque [N.m]; never above the joint's effort, the
  /// spine's own limit (0: the effort).
  double max_torque = 0.0;
  /// Above Upkie's largest effort (16 N.m) the cap is the effort anyway.
  static constexpr LimitRange kMaxTorqueRange{0.0, 100.0};
  /// The spine is silent when a request stays unanswered this long [s].
  double spine_timeout = 0.1;
  /// A silent spine must be noticed within seconds.
  static constexpr LimitRange kSpineTimeoutRange{0.001, 10.0};
  /// Stop after this many missed deadlines in a row (a cycle longer than 1.5 periods).
  /// (20 cycles of a 200 Hz task: 100 ms, the spine's own timeout, at least 50 ms late.)
  int max_consecutive_deadline_misses = 20;
  /// 2000 cycles: 10 s at 200 Hz, as long as the longest spine timeout.
  static constexpr LimitRange kMaxDeadlineMissesRange{1.0, 2000.0};
  /// Stop after any one cycle longer than this many periods (20: 100 ms at 200 Hz).
  double max_cycle_periods = 20.0;
  /// From 2 (a cycle of 1.5 periods is already a missed deadline) to 10 s at 200 Hz.
  static constexpr LimitRange kMaxCyclePeriodsRange{2.0, 2000.0};
  /// Cycles of stop commands (zero wheel velocity, legs held) sent before the Stop request.
  int nb_stop_cycles = 5;
  /// 200 cycles: 1 s at 200 Hz, 4 s at 50 Hz (the velocity task, the slowest), ample for
  /// the wheels to come to rest; the bound keeps a stopping runner's exit within seconds.
  static constexpr LimitRange kStopCyclesRange{0.0, 200.0};

  /// @throws AgentError naming the first limit outside its range (or not finite).
  void validate() const;
};

}  // namespace upkie_rl

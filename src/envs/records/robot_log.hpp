#pragma once
/// @file
/// RobotLog: a recorded run read back, whoever recorded it: a spine log (Upkie's spines,
/// `upkie-rl spine --log`) or a record file (`upkie-rl rollout --record`,
/// `upkie-rl-agent --record`). Engine-free, so that the robot runner could link it.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "spine/spine_log.hpp"

namespace upkie_rl {

/// What a log holds besides time and pitch (which every log has).
struct LoggedSignals {
  bool servo_measurements = false;  ///< Joint positions and velocities of the six servos.
  bool servo_commands = false;      ///< The six servo commands (a spine log, a servos env).
  bool pitch_rate = false;          ///< The base's angular velocity about its y axis.
};

/// The cycles of a recorded run, in time order, from one episode.
struct RobotLog {
  std::string name;    ///< The file, for messages.
  std::string format;  ///< "spine log" or "record file".
  LoggedSignals signals;
  std::vector<LoggedCycle> cycles;

  /// The median time between cycles [s].
  double period() const;
  /// Duration from the first cycle to the last [s].
  double duration() const { return cycles.back().time - cycles.front().time; }
  /// @throws RobotLogError when a time step differs from period() by more than 25 %
  ///         (cycles dropped, or a log at another rate spliced in), naming the cycle.
  void check_regular() const;
};

/// Reads a spine log (a MessagePack stream) or a record file (CSV), told apart by their
/// first byte.
/// @throws RobotLogError, one line naming the file and the problem (see read_spine_log and
///         read_record_log).
RobotLog read_robot_log(const std::filesystem::path& path);

/// A record file's columns read into cycles: `t`, `pitch` and `ground_position` (required),
/// the servos environment's `<joint>.position`/`.velocity`/`.torque` and
/// `action.<joint>.<field>` columns, the pendulum's `theta_dot` and `p_dot` or the velocity
/// task's `gyro.y` when present. Only the first episode is read.
/// @throws RobotLogError naming the line and column: a missing column, a field that is not a
///         number, a NaN or impossible (1e308) value, a row of the wrong length, time that
///         does not increase, fewer than 2 rows.
RobotLog read_record_log(std::string_view text, const std::string& name);

}  // namespace upkie_rl

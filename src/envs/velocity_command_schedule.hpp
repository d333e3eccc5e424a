#pragma once
/// @file
/// VelocityCommandSchedule: a scripted sequence of velocity commands (`rollout --commands`),
/// so that controllers are compared on the same commands.

#include <filesystem>
#include <string>
#include <vector>

#include "envs/velocity_command.hpp"

namespace upkie_rl {

/// Piecewise-constant commands: row i holds from its time until the next row's.
class VelocityCommandSchedule {
 public:
  struct Row {
    double time = 0.0;  ///< [s] since reset
    VelocityCommand command;
  };

  /// @throws std::invalid_argument when there are no rows, a value is not finite, or the
  ///         times are negative or not increasing.
  explicit VelocityCommandSchedule(std::vector<Row> rows);

  /// Reads a CSV file of rows `time,vx,wz` ([s], [m/s], [rad/s]); the first line that is
  /// neither blank nor a comment may be a header (not numbers); blank lines and lines starting with
  /// '#' are skipped.
  /// @throws std::invalid_argument naming the file and line of a malformed row, or as the
  ///         constructor.
  static VelocityCommandSchedule load(const std::filesystem::path& path);

  /// The command at `time`: the last row whose time is at most `time` (the first row's
  /// before it).
  const VelocityCommand& at(double time) const;

  const std::vector<Row>& rows() const { return rows_; }

 private:
  std::vector<Row> rows_;
};

}  // namespace upkie_rl

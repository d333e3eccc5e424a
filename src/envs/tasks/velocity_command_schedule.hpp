#pragma once
/// @file
/// VelocityCommandSchedule: a scripted sequence of velocity commands (`rollout --commands`),
/// so that controllers are compared on the same commands.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "envs/tasks/velocity_command.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"

namespace upkie_rl {

/// Largest velocity command file read: a row takes about 20 bytes, so 1 MiB holds some 50,000
/// rows, hours of script.
inline constexpr std::uintmax_t kMaxCommandFileBytes = std::uintmax_t{1} << 20;

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

  /// Reads a CSV file of rows `time,vx,wz` or `time,vx,wz,height` ([s], [m/s], [rad/s],
  /// [m]; a row without height: ranges.max_height, standing by default) of at most
  /// kMaxCommandFileBytes; the first line that is neither blank nor a comment may be a header
  /// (not numbers); blank lines and lines starting with '#' are skipped. Every time must be in
  /// [0, kOptionHuge], every vx in ±ranges.max_forward_velocity and every wz in
  /// ±ranges.max_yaw_rate, every height in [ranges.min_height, ranges.max_height] with
  /// ranges.height_command (none without it) (the task's command ranges: a command the task
  /// never draws is a typo, and 1e30 would only make the summary's errors 1e30).
  /// @throws std::invalid_argument naming the file, line, column and value at fault, a file
  ///         that is not regular or too large, or as the constructor.
  static VelocityCommandSchedule load(const std::filesystem::path& path,
                                      const VelocityCommandRanges& ranges);

  /// The command at `time`: the last row whose time is at most `time` (the first row's
  /// before it).
  const VelocityCommand& at(double time) const;

  const std::vector<Row>& rows() const { return rows_; }

 private:
  std::vector<Row> rows_;
};

}  // namespace upkie_rl

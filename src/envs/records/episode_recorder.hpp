#pragma once
/// @file
/// EpisodeRecorder: the CSV file of `upkie-rl rollout --record` and of the robot runner's
/// flight recorder (`upkie-rl-agent --record`).

#include <array>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "envs/core/env.hpp"
#include "envs/records/record_columns.hpp"
#include "envs/tasks/velocity_command.hpp"

namespace upkie_rl {

/// One row per step (columns declared in envs/records/record_columns.hpp): episode, step, t, each
/// observation component by name, each action component by name ("action.<name>"), reward,
/// terminated, truncated, then the simulator's ground truth base_x, base_y, base_z, base_qw,
/// base_qx, base_qy, base_qz and the six joint angles by joint name (NaN when the backend has no
/// ground truth), then the base pitch and the wheel odometry's ground position, then for a velocity
/// task the measured base velocity (kMeasuredVelocityColumns; the command is in the observation's
/// columns), then the caller's extra columns if any. A row holds the observation the controller saw
/// at time t, the ground truth at that time, the action it chose, and the reward and flags of the
/// step that action made.
class EpisodeRecorder {
 public:
  /// Opens (truncates) `path`, so that a bad path is refused before anything runs.
  /// @throws std::runtime_error naming the path when it cannot be written.
  explicit EpisodeRecorder(const std::filesystem::path& path);

  /// Writes the header row for `env`'s spaces, then `extra_columns` (a caller's own, e.g.
  /// the robot runner's supervisor state and loop timing).
  void write_header(const Env& env, std::span<const std::string> extra_columns = {});

  /// Remembers t, the observation and the ground truth before a step.
  void before_step(const Env& env, std::span<const float> observation);

  /// Writes the row of the step, ending with `extra` (one value per extra column).
  /// @throws std::invalid_argument when `extra` does not have one value per extra column.
  void after_step(int episode, int step, std::span<const float> action, const StepResult& result,
                  std::span<const double> extra = {});

  /// Flushes; @throws std::runtime_error naming the path on a write error.
  void close();

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::vector<float> observation_;
  double time_ = 0.0;
  RecordedPose pose_;
  RecordedMeasurement measurement_;
  bool velocity_task_ = false;  ///< Whether the header has the measured velocity columns.
  BaseVelocity measured_velocity_;
  std::size_t num_extra_columns_ = 0;
};

}  // namespace upkie_rl
